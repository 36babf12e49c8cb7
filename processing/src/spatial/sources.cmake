# processing/spatial: neighbour search: k-d tree, k-NN graph, voxel grid, the cloud store, and
# the triangle tree (closest point on a mesh; CGAL only in triangle_tree.cpp).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/spatial/cloud_store.cpp
    src/spatial/kdtree.cpp
    src/spatial/knn_cells.cpp
    src/spatial/knn_select.cpp
    src/spatial/neighbor_graph.cpp
    src/spatial/triangle_tree.cpp
    src/spatial/voxel_grid.cpp
)
