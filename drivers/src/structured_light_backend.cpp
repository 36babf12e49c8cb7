// The `sl:` backend: a structured-light scanner composed of a GLFW projector window and
// two cameras named by URI, with an OpenCV YAML stereo calibration.
#include "anascan/drivers/projector_output.hpp"
#include "anascan/drivers/structured_light_scanner.hpp"
#include "uri_query.hpp"

namespace anascan::drivers {
namespace {

Expected<UriQuery> parse_sl_target(const std::string& uri, const std::string& target) {
    auto q = parse_uri_query(uri, target,
                             {"cam1", "cam2", "projector", "phase_steps", "phase_period_px",
                              "latency_ms", "swap_cameras"});
    if (!q) return q;
    if (q->path.empty() || !q->values.contains("cam1") || !q->values.contains("cam2"))
        return fail(ErrorCode::kInvalidArgument,
                    uri + ": expected sl:CALIBRATION.yml?cam1=URI&cam2=URI[&projector=N]");
    return q;
}

/// Opens `uri` as a camera streaming the calibration's image size (grey8 preferred).
Expected<std::unique_ptr<Camera>> open_camera(const DeviceRegistry& cameras, const std::string& uri,
                                              const sl::CameraIntrinsics& size) {
    auto opened = open_as_camera(cameras, uri);
    if (!opened) return opened;
    std::unique_ptr<Camera> camera = std::move(*opened);
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
                                        const UriQuery& t) {
    StructuredLightParts parts;
    parts.info = {.uri = uri, .model = "structured-light scanner (projector + 2 cameras)"};
    auto swap = query_int(t, "swap_cameras", 0, uri);
    auto monitor = query_int(t, "projector", -1, uri);
    auto steps = query_int(t, "phase_steps", 0, uri);
    auto period = query_int(t, "phase_period_px", 16, uri);
    auto latency = query_int(t, "latency_ms", 0, uri);
    for (const auto* v : {&swap, &monitor, &steps, &period, &latency})
        if (!*v) return fail(v->error());
    auto calibration = sl::load_stereo_calibration(t.path, {.swap_cameras = *swap != 0});
    if (!calibration)
        return fail(calibration.error().code, uri + ": " + calibration.error().message);
    parts.calibration = *calibration;
    auto cam1 = open_camera(cameras, t.values.at("cam1"), calibration->cam1);
    if (!cam1) return fail(cam1.error().code, uri + ": cam1: " + cam1.error().message);
    auto cam2 = open_camera(cameras, t.values.at("cam2"), calibration->cam2);
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
