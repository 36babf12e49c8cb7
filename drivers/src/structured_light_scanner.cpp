#include "anascan/drivers/structured_light_scanner.hpp"

#include <algorithm>
#include <cstdio>

#include "frame_grey.hpp"

namespace anascan::drivers {
namespace {

std::string part_name(const char* label, const Camera& camera) {
    return std::string(label) + " (" + camera.info().uri + ")";
}

std::vector<Pattern> to_patterns(const std::vector<cv::Mat>& images) {
    std::vector<Pattern> patterns;
    patterns.reserve(images.size());
    for (const cv::Mat& m : images) {
        Pattern p{m.cols, m.rows, {}};
        const cv::Mat c = m.isContinuous() ? m : m.clone();
        p.grey.assign(c.data, c.data + c.total());
        patterns.push_back(std::move(p));
    }
    return patterns;
}

Capabilities scanner_capabilities(const StructuredLightParts& parts) {
    Capabilities caps;
    caps.can_capture_scan = true;
    caps.range_m = parts.range_m;
    const auto& e1 = parts.cam1->capabilities().exposure_us;
    const auto& e2 = parts.cam2->capabilities().exposure_us;
    if (e1 && e2 && std::max(e1->min, e2->min) <= std::min(e1->max, e2->max))
        caps.exposure_us = NumericRange{std::max(e1->min, e2->min), std::min(e1->max, e2->max)};
    return caps;
}

Expected<void> check_camera_size(const char* label, const Camera& camera,
                                 const sl::CameraIntrinsics& calibration) {
    const auto& profile = camera.settings().profile;
    if (!profile ||
        (profile->width == calibration.width_px && profile->height == calibration.height_px))
        return {};
    return fail(ErrorCode::kInvalidArgument,
                part_name(label, camera) + " streams " + std::to_string(profile->width) + " x " +
                    std::to_string(profile->height) + " px, the calibration is for " +
                    std::to_string(calibration.width_px) + " x " +
                    std::to_string(calibration.height_px) + " px");
}

}  // namespace

StructuredLightScanner::StructuredLightScanner(StructuredLightParts parts)
    : parts_(std::move(parts)) {
    parts_.info.kind = DeviceKind::kStructuredLight;
    parts_.info.is_scanner = true;
    parts_.info.is_camera = false;
    caps_ = scanner_capabilities(parts_);
    min_range_m_ = parts_.range_m.min;
    max_range_m_ = parts_.range_m.max;
}

Expected<std::unique_ptr<StructuredLightScanner>> StructuredLightScanner::create(
    StructuredLightParts parts) {
    const std::string& uri = parts.info.uri;
    if (!parts.projector || !parts.cam1 || !parts.cam2)
        return fail(ErrorCode::kInvalidArgument, uri + ": a projector and two cameras are needed");
    if (auto ok = check_camera_size("cam1", *parts.cam1, parts.calibration.cam1); !ok)
        return fail(ok.error().code, uri + ": " + ok.error().message);
    if (auto ok = check_camera_size("cam2", *parts.cam2, parts.calibration.cam2); !ok)
        return fail(ok.error().code, uri + ": " + ok.error().message);
    const sl::GrayCodeLayout& layout = parts.decode.sequence.gray;
    if (parts.projector->width_px() != layout.projector_width_px ||
        parts.projector->height_px() != layout.projector_height_px)
        return fail(ErrorCode::kInvalidArgument,
                    uri + ": " + parts.projector->name() + " is " +
                        std::to_string(parts.projector->width_px()) + " x " +
                        std::to_string(parts.projector->height_px()) + " px, the pattern layout " +
                        std::to_string(layout.projector_width_px) + " x " +
                        std::to_string(layout.projector_height_px) + " px");
    std::unique_ptr<StructuredLightScanner> scanner(new StructuredLightScanner(std::move(parts)));
    scanner->patterns_ = to_patterns(sl::make_patterns(scanner->parts_.decode.sequence));
    if (auto ok = scanner->parts_.projector->load(scanner->patterns_); !ok)
        return fail(ok.error().code, uri + ": " + ok.error().message);
    return scanner;
}

DeviceSettings StructuredLightScanner::settings() const {
    DeviceSettings s;
    if (caps_.exposure_us) s.exposure_us = parts_.cam1->settings().exposure_us;
    s.min_range_m = min_range_m_;
    s.max_range_m = max_range_m_;
    return s;
}

Expected<void> StructuredLightScanner::configure(const DeviceSettings& requested) {
    if (closed_ || disconnected_)
        return fail(ErrorCode::kDisconnected,
                    parts_.info.uri + (closed_ ? ": closed" : ": a part went away"));
    const DeviceSettings merged = merge_settings(settings(), requested);
    if (auto ok = validate_settings(merged, caps_, parts_.info.uri); !ok) return ok;
    if (*merged.min_range_m > *merged.max_range_m)
        return fail(ErrorCode::kInvalidArgument,
                    parts_.info.uri + ": min_range_m is above max_range_m");
    if (requested.exposure_us) {
        const DeviceSettings exposure{.exposure_us = requested.exposure_us};
        if (auto ok = parts_.cam1->configure(exposure); !ok) return ok;
        if (auto ok = parts_.cam2->configure(exposure); !ok) return ok;
    }
    min_range_m_ = *merged.min_range_m;
    max_range_m_ = *merged.max_range_m;
    return {};
}

std::string StructuredLightScanner::calibration_json() const {
    const sl::StereoCalibration& c = parts_.calibration;
    const sl::PatternSequence& s = parts_.decode.sequence;
    char json[512];
    std::snprintf(json, sizeof(json),
                  "{\"camera_size_px\": [%d, %d], \"camera_focal_px\": %g, \"baseline_m\": %g, "
                  "\"projector_size_px\": [%d, %d], \"phase_steps\": %d, "
                  "\"phase_period_px\": %d}",
                  c.cam1.width_px, c.cam1.height_px, c.cam1.K(0, 0),
                  c.T_cam1_cam2.translation().norm(), s.gray.projector_width_px,
                  s.gray.projector_height_px, s.phase ? s.phase->steps : 0,
                  s.phase ? s.phase->period_px : 0);
    return json;
}

void StructuredLightScanner::close() {
    parts_.cam1->close();
    parts_.cam2->close();
    closed_ = true;
}

Error StructuredLightScanner::gone(const Error& error) {
    if (error.code == ErrorCode::kDisconnected) disconnected_ = true;
    return Error{error.code, parts_.info.uri + ": " + error.message};
}

}  // namespace anascan::drivers
