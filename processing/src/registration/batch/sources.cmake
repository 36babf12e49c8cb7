# processing/registration/batch: registration of N unordered scans (paper §4, batch form).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/registration/batch/bridging.cpp
    src/registration/batch/confirmation.cpp
    src/registration/batch/gate.cpp
    src/registration/batch/graph.cpp
    src/registration/batch/prepare.cpp
    src/registration/batch/pruning.cpp
    src/registration/batch/records.cpp
    src/registration/batch/scan_registration.cpp
    src/registration/batch/slides.cpp
    src/registration/batch/store.cpp
)
