#include "anascan/acquisition/store/stone_check.hpp"

namespace anascan::acquisition {

std::string stone_of_device(std::string_view device_uri) {
    if (!device_uri.starts_with("sim:")) return {};
    const std::size_t slash = device_uri.find('/');
    if (slash == std::string_view::npos) return {};
    std::string_view scene = device_uri.substr(slash + 1);
    scene = scene.substr(0, scene.find_first_of("?#"));
    constexpr std::string_view kTurned = "-turned";
    if (scene.ends_with(kTurned)) scene.remove_suffix(kTurned.size());
    return std::string(scene);
}

std::optional<std::string> another_stone_reason(const std::vector<DeviceRecord>& devices,
                                                std::string_view device_uri) {
    const std::string stone = stone_of_device(device_uri);
    if (stone.empty()) return std::nullopt;
    for (const DeviceRecord& device : devices) {
        const std::string before = stone_of_device(device.id);
        if (before.empty() || before == stone) continue;
        return "the session's scans so far show the stone '" + before + "' (from " + device.id +
               "), and " + std::string(device_uri) + " looks at '" + stone + "'";
    }
    return std::nullopt;
}

}  // namespace anascan::acquisition
