# acquisition/live: on-site registration of each new scan (the live registrar).
list(APPEND ANASCAN_ACQUISITION_SOURCES
    src/live/consistency.cpp
    src/live/consistency_split.cpp
    src/live/device_scale.cpp
    src/live/hypotheses.cpp
    src/live/json.cpp
    src/live/links.cpp
    src/live/live_registration.cpp
    src/live/memory.cpp
    src/live/merge.cpp
    src/live/prepare.cpp
    src/live/refine.cpp
    src/live/sequence_merge.cpp
    src/live/votes.cpp
)
