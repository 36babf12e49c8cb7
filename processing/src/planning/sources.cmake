# processing/planning: the next-best-view from the current coverage.
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/planning/candidates.cpp
    src/planning/envelope.cpp
    src/planning/frame.cpp
    src/planning/hint_text.cpp
    src/planning/next_best_view.cpp
    src/planning/visibility.cpp
)
