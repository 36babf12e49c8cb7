#pragma once
// JSON files of the blocks folder: read (errors name the file), write crash-safely.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "anascan/processing/core/expected.hpp"

namespace anascan::acquisition::blocks_detail {

Expected<nlohmann::json> read_json(const std::filesystem::path& path);
Expected<void> write_json(const std::filesystem::path& path, const nlohmann::json& j);

}  // namespace anascan::acquisition::blocks_detail
