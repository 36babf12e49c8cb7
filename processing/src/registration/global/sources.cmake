# processing/registration/global: global pairwise registration from features (paper §4.2.1).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/registration/global/consensus.cpp
    src/registration/global/features.cpp
    src/registration/global/global_registration.cpp
    src/registration/global/matching.cpp
)
