# acquisition/blocks: folders of block features, proposals and the alignment of blocks as
# the commands and the field app's assembly view run it.
list(APPEND ANASCAN_ACQUISITION_SOURCES
    src/blocks/block_alignment.cpp
    src/blocks/block_features_file.cpp
    src/blocks/block_folder.cpp
    src/blocks/block_models.cpp
    src/blocks/block_proposals.cpp
    src/blocks/json_file.cpp
)
