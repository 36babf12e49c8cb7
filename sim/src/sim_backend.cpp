#include "anascan/sim/sim_backend.hpp"

#include "anascan/sim/sim_structured_light_scanner.hpp"
#include "anascan/sim/sim_tof_scanner.hpp"

namespace anascan::sim {
namespace {

struct SimTarget {
    std::string model;  ///< "tof" or "structured-light".
    std::string scene;
};

SimTarget split_target(const std::string& target) {
    const auto slash = target.find('/');
    if (slash == std::string::npos) return {target, std::string(kDefaultSimScene)};
    return {target.substr(0, slash), target.substr(slash + 1)};
}

}  // namespace

Expected<SimDeviceTarget> sim_device_target(const std::string& uri) {
    auto parsed = drivers::parse_device_uri(uri);
    if (!parsed) return fail(parsed.error());
    if (parsed->scheme != "sim")
        return fail(ErrorCode::kInvalidArgument, uri + ": not a simulated device (sim:...)");
    const SimTarget target = split_target(parsed->target);
    if (target.model != "tof" && target.model != "structured-light")
        return fail(ErrorCode::kUnsupported,
                    uri + ": no such simulated device (known: sim:tof, sim:structured-light)");
    auto scene = named_scene(target.scene);
    if (!scene) return fail(scene.error().code, uri + ": " + scene.error().message);
    return SimDeviceTarget{.terrestrial = target.model == "tof", .scene = *scene};
}

Expected<std::unique_ptr<drivers::Device>> open_sim_device(
    const drivers::DeviceUri& uri, const std::shared_ptr<SimWorldCache>& worlds) {
    const std::string text = drivers::to_string(uri);
    const SimTarget target = split_target(uri.target);
    if (target.model != "tof" && target.model != "structured-light")
        return fail(ErrorCode::kUnsupported,
                    text + ": no such simulated device (known: sim:tof, sim:structured-light)");
    auto scene = named_scene(target.scene);
    if (!scene) return fail(scene.error().code, text + ": " + scene.error().message);
    if (target.model == "tof")
        return std::unique_ptr<drivers::Device>(
            SimTofScanner::open({.uri = text, .scene = *scene, .worlds = worlds}));
    return std::unique_ptr<drivers::Device>(
        SimStructuredLightScanner::open({.uri = text, .scene = *scene, .worlds = worlds}));
}

drivers::Backend make_sim_backend() {
    auto worlds = std::make_shared<SimWorldCache>();
    return drivers::Backend{
        .scheme = "sim",
        .description =
            "simulated scanners looking at a stone block: sim:tof, "
            "sim:structured-light, sim:tof/SCENE (anascan sim list-scenes)",
        .enumerate =
            [worlds] {
                // Opening is cheap (the scene is built at the first capture).
                std::vector<drivers::DeviceInfo> devices;
                for (const char* uri : {"sim:tof", "sim:structured-light"})
                    devices.push_back(
                        (*open_sim_device(*drivers::parse_device_uri(uri), worlds))->info());
                return devices;
            },
        .open = [worlds](const drivers::DeviceUri& uri) { return open_sim_device(uri, worlds); }};
}

}  // namespace anascan::sim
