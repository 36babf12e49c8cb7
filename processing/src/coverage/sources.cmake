# processing/coverage: coverage of a stone's surface by registered scans, and its holes.
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/coverage/bins.cpp
    src/coverage/cluster.cpp
    src/coverage/coverage.cpp
    src/coverage/holes.cpp
    src/coverage/hull.cpp
    src/coverage/json.cpp
    src/coverage/observation.cpp
    src/coverage/sampling.cpp
    src/coverage/stone.cpp
)
