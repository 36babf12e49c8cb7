# Block features of a 1 M-point block and matching all face pairs of 150 blocks; the peer
# is Open3D's RANSAC plane segmentation (one plane at a time, removing its inliers), run
# on the same points in the same process. Included from tests/bench/CMakeLists.txt.
find_package(benchmark QUIET)
if(benchmark_FOUND)
    add_executable(anascan_bench_reassembly ${CMAKE_CURRENT_LIST_DIR}/bench_reassembly.cpp)
    target_link_libraries(anascan_bench_reassembly PRIVATE anascan::sim benchmark::benchmark)
    find_package(Open3D QUIET)
    if(Open3D_FOUND)
        target_link_libraries(anascan_bench_reassembly PRIVATE Open3D::Open3D)
        target_compile_definitions(anascan_bench_reassembly PRIVATE ANASCAN_HAVE_OPEN3D=1)
    endif()
    anascan_set_warnings(anascan_bench_reassembly)
endif()
