# processing/surface: fragment models (screened Poisson through Open3D, support and class of
# every vertex and triangle, topology and the model report).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/surface/fit_to_points.cpp
    src/surface/fragment_model.cpp
    src/surface/merge.cpp
    src/surface/mesh_distance.cpp
    src/surface/mesh_measures.cpp
    src/surface/mesh_topology.cpp
    src/surface/model_report.cpp
    src/surface/oriented_box.cpp
    src/surface/poisson.cpp
    src/surface/reconstruction.cpp
    src/surface/subdivide.cpp
    src/surface/support.cpp
    src/surface/truth_comparison.cpp
    src/surface/truth_visibility.cpp
)
