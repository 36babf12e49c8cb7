# `anascan sl decode` (the whole command, as a process) against OpenCV's Gray-code path
# (imread + rectify + GrayCodePattern::decode + reprojectImageTo3D) on the GSoC statue data.
# Included from tests/bench/CMakeLists.txt; needs the structured-light test support library.
if(TARGET anascan_sl_test_support)
    add_executable(anascan_bench_sl_decode ${CMAKE_CURRENT_LIST_DIR}/bench_sl_decode.cpp)
    target_link_libraries(anascan_bench_sl_decode PRIVATE anascan_sl_test_support)
    add_dependencies(anascan_bench_sl_decode anascan)
    target_compile_definitions(anascan_bench_sl_decode PRIVATE
        ANASCAN_CLI="$<TARGET_FILE:anascan>"
        ANASCAN_STATUE_DIR="${PROJECT_SOURCE_DIR}/../shared/data/gsoc2015-statue-graycode-stereo")
    anascan_set_warnings(anascan_bench_sl_decode)
endif()
