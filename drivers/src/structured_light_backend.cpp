// The `sl:` backend: a structured-light scanner composed of a GLFW projector window and
// two cameras named by URI, with an OpenCV YAML stereo calibration.
#include <charconv>
#include <map>

#include "anascan/drivers/projector_output.hpp"
#include "anascan/drivers/structured_light_scanner.hpp"

namespace anascan::drivers {
namespace {

/// `sl:` target split into the calibration path and the query's key=value pairs.
struct SlTarget {
    std::string calibration;
    std::map<std::string, std::string> query;
};

Expected<SlTarget> parse_sl_target(const std::string& uri, const std::string& target) {
    SlTarget t;
    const std::size_t q = target.find('?');
    t.calibration = target.substr(0, q);
    std::string rest = q == std::string::npos ? "" : target.substr(q + 1);
    while (!rest.empty()) {
        const std::size_t amp = rest.find('&');
        const std::string item = rest.substr(0, amp);
        const std::size_t eq = item.find('=');
        if (eq == std::string::npos || eq == 0)
            return fail(ErrorCode::kInvalidArgument,
                        uri + ": '" + item + "' is not KEY=VALUE (e.g. cam1=v4l2:/dev/video2)");
        t.query[item.substr(0, eq)] = item.substr(eq + 1);
        rest = amp == std::string::npos ? "" : rest.substr(amp + 1);
    }
    for (const auto& [key, value] : t.query)
        if (key != "cam1" && key != "cam2" && key != "projector" && key != "phase_steps" &&
            key != "phase_period_px" && key != "latency_ms" && key != "swap_cameras")
            return fail(ErrorCode::kInvalidArgument,
                        uri + ": unknown key '" + key +
                            "' (known: cam1, cam2, projector, phase_steps, phase_period_px, "
                            "latency_ms, swap_cameras)");
    if (t.calibration.empty() || !t.query.contains("cam1") || !t.query.contains("cam2"))
        return fail(ErrorCode::kInvalidArgument,
                    uri + ": expected sl:CALIBRATION.yml?cam1=URI&cam2=URI[&projector=N]");
    return t;
}

Expected<int> int_value(const SlTarget& t, const std::string& key, int fallback,
                        const std::string& uri) {
    const auto it = t.query.find(key);
    if (it == t.query.end()) return fallback;
    int v = 0;
    const auto [end, ec] =
        std::from_chars(it->second.data(), it->second.data() + it->second.size(), v);
    if (ec != std::errc() || end != it->second.data() + it->second.size())
        return fail(ErrorCode::kInvalidArgument,
                    uri + ": " + key + "=" + it->second + " is not an integer");
    return v;
}

/// Opens `uri` as a camera streaming the calibration's image size (grey8 preferred).
Expected<std::unique_ptr<Camera>> open_camera(const DeviceRegistry& cameras, const std::string& uri,
                                              const sl::CameraIntrinsics& size) {
    auto device = cameras.open(uri);
    if (!device) return fail(device.error());
    if ((*device)->as_camera() == nullptr)
        return fail(ErrorCode::kUnsupported, uri + ": not a camera");
    std::unique_ptr<Camera> camera((*device)->as_camera());
    (void)device->release();
    std::optional<StreamProfile> best;
    for (const StreamProfile& p : camera->capabilities().profiles)
        if (p.width == size.width_px && p.height == size.height_px &&
            p.format != PixelFormat::kZ16 &&
            (!best || (best->format != PixelFormat::kGrey8 && p.format == PixelFormat::kGrey8)))
            best = p;
    if (best) {
        if (auto ok = camera->configure({.profile = best}); !ok) return fail(ok.error());
    }
    return camera;
}

Expected<StructuredLightParts> sl_parts(const DeviceRegistry& cameras, const std::string& uri,
                                        const SlTarget& t) {
    StructuredLightParts parts;
    parts.info = {.uri = uri, .model = "structured-light scanner (projector + 2 cameras)"};
    auto swap = int_value(t, "swap_cameras", 0, uri);
    auto monitor = int_value(t, "projector", -1, uri);
    auto steps = int_value(t, "phase_steps", 0, uri);
    auto period = int_value(t, "phase_period_px", 16, uri);
    auto latency = int_value(t, "latency_ms", 0, uri);
    for (const auto* v : {&swap, &monitor, &steps, &period, &latency})
        if (!*v) return fail(v->error());
    auto calibration = sl::load_stereo_calibration(t.calibration, {.swap_cameras = *swap != 0});
    if (!calibration) return fail(calibration.error());
    parts.calibration = *calibration;
    auto cam1 = open_camera(cameras, t.query.at("cam1"), calibration->cam1);
    if (!cam1) return fail(cam1.error().code, uri + ": cam1: " + cam1.error().message);
    auto cam2 = open_camera(cameras, t.query.at("cam2"), calibration->cam2);
    if (!cam2) return fail(cam2.error().code, uri + ": cam2: " + cam2.error().message);
    auto projector = ProjectorOutput::open({.monitor_index = *monitor});
    if (!projector) return fail(projector.error().code, uri + ": " + projector.error().message);
    parts.cam1 = std::move(*cam1);
    parts.cam2 = std::move(*cam2);
    parts.decode.sequence.gray = {.projector_width_px = (*projector)->width_px(),
                                  .projector_height_px = (*projector)->height_px()};
    if (*steps > 0)
        parts.decode.sequence.phase = sl::PhaseShiftLayout{.period_px = *period, .steps = *steps};
    parts.projector = std::move(*projector);
    parts.frame_latency = std::chrono::milliseconds(*latency);
    return parts;
}

}  // namespace

Backend make_structured_light_backend(std::shared_ptr<const DeviceRegistry> cameras) {
    return Backend{.scheme = "sl",
                   .description =
                       "structured-light scanner: projector + two cameras, "
                       "sl:CALIBRATION.yml?cam1=v4l2:/dev/video2&cam2=v4l2:/dev/video3"
                       "[&projector=MONITOR][&phase_steps=N&phase_period_px=P]",
                   .enumerate = [] { return std::vector<DeviceInfo>{}; },
                   .open = [cameras](const DeviceUri& uri) -> Expected<std::unique_ptr<Device>> {
                       const std::string text = to_string(uri);
                       auto target = parse_sl_target(text, uri.target);
                       if (!target) return fail(target.error());
                       auto parts = sl_parts(*cameras, text, *target);
                       if (!parts) return fail(parts.error());
                       auto scanner = StructuredLightScanner::create(std::move(*parts));
                       if (!scanner) return fail(scanner.error());
                       return std::unique_ptr<Device>(std::move(*scanner));
                   }};
}

}  // namespace anascan::drivers
