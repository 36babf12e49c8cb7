#include "anascan/drivers/device_registry.hpp"

#include <algorithm>

namespace anascan::drivers {

Expected<void> DeviceRegistry::add(Backend backend) {
    if (!backend.enumerate || !backend.open) {
        return fail(ErrorCode::kInvalidArgument,
                    "backend '" + backend.scheme + "' lacks an enumerate or open function");
    }
    const bool taken = std::any_of(backends_.begin(), backends_.end(),
                                   [&](const Backend& b) { return b.scheme == backend.scheme; });
    if (taken) {
        return fail(ErrorCode::kInvalidArgument,
                    "a backend for scheme '" + backend.scheme + "' is already registered");
    }
    backends_.push_back(std::move(backend));
    return {};
}

std::vector<DeviceInfo> DeviceRegistry::enumerate() const {
    std::vector<DeviceInfo> all;
    for (const Backend& b : backends_) {
        std::vector<DeviceInfo> found = b.enumerate();
        all.insert(all.end(), found.begin(), found.end());
    }
    return all;
}

Expected<std::unique_ptr<Device>> DeviceRegistry::open(std::string_view text) const {
    auto uri = parse_device_uri(text);
    if (!uri) return fail(uri.error());
    for (const Backend& b : backends_) {
        if (b.scheme == uri->scheme) return b.open(*uri);
    }
    std::string known;
    for (const Backend& b : backends_) known += (known.empty() ? "" : ", ") + b.scheme + ":";
    return fail(ErrorCode::kUnsupported, "device '" + std::string(text) + "': no backend for '" +
                                             uri->scheme + ":' (known: " + known + ")");
}

}  // namespace anascan::drivers
