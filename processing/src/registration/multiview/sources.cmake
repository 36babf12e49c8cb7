# processing/registration/multiview: multi-view refinement and compact links (paper §4.2.4).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/registration/multiview/link_compression.cpp
    src/registration/multiview/multiview_refinement.cpp
    src/registration/multiview/steps.cpp
)
