# Fine registration benchmark: bun045 -> bun000 from a 5 deg / 5 mm start, anascan against
# Open3D's RegistrationICP (point-to-plane, 5 mm) with the same target normals, in one run.
# Included from tests/bench/CMakeLists.txt after Google Benchmark was found.
# Run: cmake --build <build> --target anascan_bench_fine_registration -j2 &&
#      <build>/tests/bench/anascan_bench_fine_registration
if(NOT DEFINED Open3D_FOUND)
    find_package(Open3D QUIET)
endif()

add_executable(anascan_bench_fine_registration
    ${CMAKE_CURRENT_LIST_DIR}/bench_fine_registration.cpp)
target_link_libraries(anascan_bench_fine_registration
    PRIVATE anascan::processing benchmark::benchmark TBB::tbb)
target_include_directories(anascan_bench_fine_registration
    PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../processing)  # test_normals_util.hpp
target_compile_definitions(anascan_bench_fine_registration
    PRIVATE ANASCAN_SHARED_DATA_DIR="${ANASCAN_SHARED_DATA_DIR}")
anascan_set_warnings(anascan_bench_fine_registration)
if(Open3D_FOUND)
    target_link_libraries(anascan_bench_fine_registration PRIVATE Open3D::Open3D)
    target_compile_definitions(anascan_bench_fine_registration PRIVATE ANASCAN_BENCH_OPEN3D=1)
else()
    message(STATUS "anascan: Open3D not found; anascan_bench_fine_registration runs alone")
endif()
