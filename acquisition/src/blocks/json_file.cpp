#include "json_file.hpp"

#include "anascan/processing/io/file_bytes.hpp"

namespace anascan::acquisition::blocks_detail {

Expected<nlohmann::json> read_json(const std::filesystem::path& path) {
    auto bytes = io::read_file_bytes(path);
    if (!bytes) return Unexpected(bytes.error());
    try {
        return nlohmann::json::parse(bytes->begin(), bytes->end());
    } catch (const nlohmann::json::exception& e) {
        return fail(ErrorCode::kFormat, path.string() + ": not JSON: " + e.what());
    }
}

Expected<void> write_json(const std::filesystem::path& path, const nlohmann::json& j) {
    const std::string text = j.dump(1) + "\n";
    return io::write_file_atomically(path, std::span<const char>(text.data(), text.size()));
}

}  // namespace anascan::acquisition::blocks_detail
