# processing/core: point clouds, scans, poses, meshes, errors, the allocator and CPU feature checks.
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/core/allocator.cpp
    src/core/cpu_features.cpp
    src/core/error.cpp
    src/core/point_cloud.cpp
    src/core/pose.cpp
    src/core/scan.cpp
)
