# acquisition/assembly: assembly of scans with known poses into one model.
list(APPEND ANASCAN_ACQUISITION_SOURCES
    src/assembly/assembly.cpp
    src/assembly/group_pulls.cpp
    src/assembly/json.cpp
    src/assembly/mesh_scans.cpp
    src/assembly/stone_frame.cpp
)
