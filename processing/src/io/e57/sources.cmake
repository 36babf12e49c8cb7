# processing/io/e57: ASTM E57 reading and writing (pages, XML with expat, bitPackCodec).
list(APPEND ANASCAN_PROCESSING_SOURCES
    src/io/e57/bytestreams.cpp
    src/io/e57/crc32c.cpp
    src/io/e57/e57_reader.cpp
    src/io/e57/e57_writer.cpp
    src/io/e57/paged_file.cpp
    src/io/e57/scan_decoder.cpp
    src/io/e57/schema.cpp
    src/io/e57/section_writer.cpp
    src/io/e57/xml_tree.cpp
)
