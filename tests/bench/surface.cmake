# Fragment models, ours against Open3D's documented Poisson path in the same run; a plain
# executable (whole-process runs of tens of seconds, not a Google Benchmark loop).
# Run: anascan_bench_surface POSES.conf REFERENCE.ply [--resolution-mm R] (see the source).
add_executable(anascan_bench_surface ${CMAKE_CURRENT_LIST_DIR}/bench_surface.cpp)
target_link_libraries(anascan_bench_surface PRIVATE anascan::processing Open3D::Open3D)
anascan_set_warnings(anascan_bench_surface)
