# processing/registration/fine: fine pairwise registration and the helical motion (paper §4.2.2).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/registration/fine/fine_registration.cpp
    src/registration/fine/helical_motion.cpp
    src/registration/fine/rating.cpp
    src/registration/fine/steps.cpp
)
