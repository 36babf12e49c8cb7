// The JSON files of the blocks folder: read (errors name the file), write crash-safely.
#include "anascan/acquisition/blocks/block_features_file.hpp"
#include "anascan/processing/io/file_bytes.hpp"

namespace anascan::acquisition {

Expected<nlohmann::json> read_json_file(const std::filesystem::path& path) {
    auto bytes = io::read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    try {
        return nlohmann::json::parse(bytes->begin(), bytes->end());
    } catch (const nlohmann::json::exception& e) {
        return fail(ErrorCode::kFormat, path.string() + ": not JSON: " + e.what());
    }
}

Expected<void> write_json_file(const std::filesystem::path& path, const nlohmann::json& j) {
    const std::string text = j.dump(1) + "\n";
    return io::write_file_atomically(path, std::span<const char>(text.data(), text.size()));
}

}  // namespace anascan::acquisition
