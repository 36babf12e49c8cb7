#pragma once
/// \file
/// Block features as JSON files (`ID.features.json`, written by `anascan blocks features`),
/// and the JSON files of the blocks commands: write crash-safely, read back with every value
/// checked (errors name the file).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "anascan/acquisition/blocks/block_folder.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/reassembly/block_features.hpp"
#include "anascan/processing/reassembly/face_matching.hpp"

namespace anascan::acquisition {

/// One block's features with its name (the model file's stem) and source file.
struct NamedBlockFeatures {
    std::string id;
    std::string source;
    reassembly::BlockFeatures features;
};

nlohmann::json to_json(const NamedBlockFeatures& block);
Expected<NamedBlockFeatures> block_features_from_json(const nlohmann::json& j,
                                                      const std::string& source_name);

/// Reads a JSON file; kIo / kFormat naming the file (and the byte, for a parse error).
Expected<nlohmann::json> read_json_file(const std::filesystem::path& path);
/// Writes a JSON file (indented), crash-safely.
Expected<void> write_json_file(const std::filesystem::path& path, const nlohmann::json& j);

/// "c0b3:2" for face 2 of block c0b3; parse_face_ref reverses it against the block ids.
std::string face_label(const std::vector<NamedBlockFeatures>& blocks, reassembly::FaceRef ref);

}  // namespace anascan::acquisition
