# processing/features: integral-invariant descriptors and feature patches (paper §4.2.1).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/features/feature_patches.cpp
    src/features/integral_invariants.cpp
    src/features/invariant_keypoints.cpp
)
