# Normal estimation + orientation, ours against Open3D in the same process.
# Included from tests/bench/CMakeLists.txt; needs Google Benchmark, uses Open3D when found.
find_package(benchmark QUIET)
if(benchmark_FOUND)
    add_executable(anascan_bench_normals ${CMAKE_CURRENT_LIST_DIR}/bench_normals.cpp)
    target_link_libraries(anascan_bench_normals PRIVATE anascan::processing
                          benchmark::benchmark)
    target_compile_definitions(anascan_bench_normals PRIVATE
        ANASCAN_BUNNY_DIR="${PROJECT_SOURCE_DIR}/../shared/data/stanford-bunny-range-scans/data")
    find_package(Open3D QUIET)
    if(Open3D_FOUND)
        target_link_libraries(anascan_bench_normals PRIVATE Open3D::Open3D)
        target_compile_definitions(anascan_bench_normals PRIVATE ANASCAN_HAVE_OPEN3D=1)
    endif()
    anascan_set_warnings(anascan_bench_normals)
endif()
