# processing/cleaning: normals and their orientation, outlier and ground-plane removal.
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/cleaning/normal_orientation.cpp
    src/cleaning/normals.cpp
    src/cleaning/normals_solve.cpp
    src/cleaning/outlier_removal.cpp
    src/cleaning/plane_removal.cpp
    src/cleaning/view_side.cpp
)
