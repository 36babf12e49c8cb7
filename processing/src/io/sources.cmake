# processing/io: file formats (PLY, XYZ/PTS, PTX, E57, Stanford .conf, .xf) and crash-safe file writes.
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/io/coverage_ply.cpp
    src/io/file_bytes.cpp
    src/io/ply_header.cpp
    src/io/ply_reader.cpp
    src/io/ply_source.cpp
    src/io/ply_vertex.cpp
    src/io/ply_writer.cpp
    src/io/ptx.cpp
    src/io/stanford_conf.cpp
    src/io/text_lines.cpp
    src/io/text_points.cpp
    src/io/xf.cpp
)
include(${CMAKE_CURRENT_LIST_DIR}/e57/sources.cmake)
