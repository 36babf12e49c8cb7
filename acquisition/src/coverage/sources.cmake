# acquisition/coverage: coverage of a session's registered scans.
list(APPEND ANASCAN_ACQUISITION_SOURCES
    src/coverage/session_coverage.cpp
)
