# Scale benchmark of register_scans (1000 synthetic scans; not a test, not in CI):
#   cmake --build <build> --target anascan_bench_register_scale
#   <build>/tests/bench/anascan_bench_register_scale --scans 1000
# Included from tests/bench/CMakeLists.txt after Google Benchmark was found.
add_executable(anascan_bench_register_scale ${CMAKE_CURRENT_LIST_DIR}/bench_register_scale.cpp)
target_link_libraries(anascan_bench_register_scale PRIVATE anascan::processing)
anascan_set_warnings(anascan_bench_register_scale)

# The multi-view stage alone at 1000 scans (memory and convergence, about a second):
#   <build>/tests/bench/anascan_bench_multiview_scale --scans 1000
add_executable(anascan_bench_multiview_scale ${CMAKE_CURRENT_LIST_DIR}/bench_multiview_scale.cpp)
target_link_libraries(anascan_bench_multiview_scale PRIVATE anascan::processing)
anascan_set_warnings(anascan_bench_multiview_scale)
