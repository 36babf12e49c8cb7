# processing/reassembly: block features (planar faces, adjacency, roughness, holes), face
# matching and neighbour proposals (method paper §5.1-5.2). CGAL only in cgal_geometry.cpp (the
# closest-point tree is spatial/triangle_tree.cpp).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/reassembly/block_features.cpp
    src/reassembly/cgal_geometry.cpp
    src/reassembly/face_adjacency.cpp
    src/reassembly/face_detection.cpp
    src/reassembly/face_holes.cpp
    src/reassembly/face_matching.cpp
    src/reassembly/face_roughness.cpp
    src/reassembly/feature_names.cpp
    src/reassembly/proposals.cpp
)
# Penetration-free alignment of neighbouring blocks (paper §5.3).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/reassembly/assembly_check.cpp
    src/reassembly/assembly_probe.cpp
    src/reassembly/assembly_qp.cpp
    src/reassembly/assembly_terms.cpp
    src/reassembly/block_assembly.cpp
    src/reassembly/constrained_lsq.cpp
    src/reassembly/horn_placement.cpp
    src/reassembly/mesh_distance.cpp
)
