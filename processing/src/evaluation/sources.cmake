# processing/evaluation: poses against truth, scan agreement, free-space checks, random poses.
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/evaluation/free_space.cpp
    src/evaluation/group_consistency.cpp
    src/evaluation/group_consistency_take_out.cpp
    src/evaluation/pose_evaluation.cpp
    src/evaluation/pose_sampling.cpp
    src/evaluation/scan_agreement.cpp
    src/evaluation/stone_identity.cpp
    src/evaluation/union_pull.cpp
)
