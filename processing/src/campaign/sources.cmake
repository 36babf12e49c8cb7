# processing/campaign: the pure stages of a scan campaign (descriptors, candidates, stones).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/campaign/candidates.cpp
    src/campaign/descriptor.cpp
    src/campaign/pairs.cpp
    src/campaign/prepare.cpp
    src/campaign/stone_graph.cpp
)
