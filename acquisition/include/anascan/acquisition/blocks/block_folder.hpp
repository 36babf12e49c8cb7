#pragma once
/// \file
/// A folder of block features (`anascan blocks features`: one ID.features.json per block,
/// naming its model) as an assembly reads it: the block ids, their models and face counts,
/// the expert's links parsed against them, and the models loaded with their features.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/reassembly/block_assembly.hpp"

namespace anascan::acquisition {

struct BlockFolder {
    std::filesystem::path dir;
    std::vector<std::filesystem::path> feature_files;  ///< Sorted by name.
    std::vector<std::string> ids;
    std::vector<std::filesystem::path> models;  ///< Each features file's `source`.
    std::vector<std::size_t> face_counts;
};

/// Reads DIR's features files; kIo when DIR is no folder or has none, kFormat naming a
/// file that is no features file.
Expected<BlockFolder> open_block_folder(const std::filesystem::path& dir);

/// "c0b3:2" (face 2 of block c0b3) against the block ids.
Expected<reassembly::FaceRef> parse_face_ref(const std::vector<std::string>& ids,
                                             const std::string& text);
/// "A:F=B:G": faces of two blocks, each listed in its features file.
Expected<reassembly::FaceLink> parse_face_link(const BlockFolder& folder, const std::string& text);
/// "A:F/G=B:H/K": the edges where faces F, G of A and H, K of B meet.
Expected<reassembly::LineLink> parse_line_link(const BlockFolder& folder, const std::string& text);

/// The links of an assembly as the expert writes them.
struct AssemblyLinks {
    std::vector<std::string> contacts;  ///< "A:F=B:G", faces that touch.
    std::vector<std::string> coplanar;  ///< "A:F=B:G", faces in one plane.
    std::vector<std::string> colinear;  ///< "A:F/G=B:H/K", edges on one line.
    std::vector<std::string> fixed;     ///< Block ids that stay in place.
};

/// The problem without its blocks' models: every link checked against the folder, so that a
/// typo fails before any model is read.
Expected<reassembly::AssemblyProblem> parse_assembly_links(const BlockFolder& folder,
                                                           const AssemblyLinks& links);

/// Called with (blocks done, blocks in all) while the models load.
using LoadProgress = std::function<void(std::size_t, std::size_t)>;

/// Reads every model first (a missing or broken one fails at once, named), then finds the
/// features again (deterministic: the face ids are the features files'). A block whose
/// features cannot be matched is an error naming its model.
Expected<std::vector<reassembly::AssemblyBlock>> load_folder_blocks(
    const BlockFolder& folder, const LoadProgress& progress = {});

}  // namespace anascan::acquisition
