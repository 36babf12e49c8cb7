# Sources of processing's core types and file formats: everything the parsers need.
# Shared by the library and by the clang/libFuzzer build in tests/fuzz/project.
set(ANASCAN_PROCESSING_CORE_SOURCES
    src/error.cpp
    src/point_cloud.cpp
    src/pose.cpp
    src/scan.cpp
    src/io/file_bytes.cpp
    src/io/ply_header.cpp
    src/io/ply_source.cpp
    src/io/ply_vertex.cpp
    src/io/ply_reader.cpp
    src/io/ply_writer.cpp
    src/io/text_points.cpp
    src/io/ptx.cpp
    src/io/stanford_conf.cpp
    src/io/xf.cpp
    src/io/text_lines.cpp)
