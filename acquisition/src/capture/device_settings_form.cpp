// The drivers' settings as the operator's form and back, and camera frames as a preview.
#include "capture/device_settings_form.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

namespace anascan::acquisition {
namespace {

using drivers::Capabilities;
using drivers::DeviceSettings;
using drivers::NumericRange;
using drivers::StreamProfile;

/// One numeric setting: where it lives in the drivers' structs and how it is shown.
struct NumericField {
    const char* key;
    const char* label;
    const char* unit;
    std::optional<NumericRange> Capabilities::*range;
    std::optional<double> DeviceSettings::*value;
};

constexpr NumericField kNumericFields[] = {
    {"exposure_us", "Exposure", "µs", &Capabilities::exposure_us, &DeviceSettings::exposure_us},
    {"gain", "Gain", "", &Capabilities::gain, &DeviceSettings::gain},
    {"angular_step_deg", "Angular step", "°", &Capabilities::angular_step_deg,
     &DeviceSettings::angular_step_deg},
    {"min_range_m", "Nearest depth", "m", &Capabilities::range_m, &DeviceSettings::min_range_m},
    {"max_range_m", "Farthest depth", "m", &Capabilities::range_m, &DeviceSettings::max_range_m},
    {"horizontal_field_deg", "Sweep width", "°", &Capabilities::horizontal_field_deg,
     &DeviceSettings::horizontal_field_deg},
    {"vertical_field_deg", "Sweep height", "°", &Capabilities::vertical_field_deg,
     &DeviceSettings::vertical_field_deg},
};

constexpr const char* kProfileKey = "profile";

std::string profile_text(const StreamProfile& p) {
    std::string text = fmt::format("{} x {} {}", p.width, p.height, drivers::to_string(p.format));
    if (p.frame_rate_hz > 0.0) text += fmt::format(" {:g} Hz", p.frame_rate_hz);
    return text;
}

Expected<void> set_number(const DeviceSetting& s, const Capabilities& caps,
                          const std::string& device, DeviceSettings& out) {
    for (const NumericField& f : kNumericFields) {
        if (s.key != f.key || !(caps.*f.range)) continue;
        if (!std::isfinite(s.value))
            return fail(ErrorCode::kInvalidArgument,
                        fmt::format("{}: {} is not a number", device, s.key));
        out.*f.value = s.value;
        return {};
    }
    return fail(ErrorCode::kInvalidArgument,
                fmt::format("{}: the device has no setting {}", device, s.key));
}

}  // namespace

DeviceSettingsForm settings_form(const drivers::Device& device) {
    const Capabilities& caps = device.capabilities();
    const DeviceSettings now = device.settings();
    DeviceSettingsForm form{.device = device.info().uri};
    for (const NumericField& f : kNumericFields) {
        if (!(caps.*f.range)) continue;
        const NumericRange range = *(caps.*f.range);
        form.settings.push_back({.key = f.key,
                                 .label = f.label,
                                 .unit = f.unit,
                                 .min = range.min,
                                 .max = range.max,
                                 .value = (now.*f.value).value_or(range.min)});
    }
    if (!caps.profiles.empty()) {
        DeviceSetting choice{
            .key = kProfileKey, .label = "Stream", .kind = DeviceSettingKind::kChoice, .choice = 0};
        for (std::size_t i = 0; i < caps.profiles.size(); ++i) {
            choice.choices.push_back(profile_text(caps.profiles[i]));
            if (now.profile && *now.profile == caps.profiles[i])
                choice.choice = static_cast<int>(i);
        }
        form.settings.push_back(std::move(choice));
    }
    return form;
}

Expected<DeviceSettings> form_settings(const DeviceSettingsForm& form, const Capabilities& caps) {
    DeviceSettings out;
    for (const DeviceSetting& s : form.settings) {
        if (s.kind == DeviceSettingKind::kNumber) {
            if (auto ok = set_number(s, caps, form.device, out); !ok) return fail(ok.error());
            continue;
        }
        if (s.key != kProfileKey)
            return fail(ErrorCode::kInvalidArgument,
                        fmt::format("{}: the device has no setting {}", form.device, s.key));
        if (s.choice < 0 || s.choice >= static_cast<int>(caps.profiles.size()))
            return fail(ErrorCode::kInvalidArgument,
                        fmt::format("{}: stream choice {} outside the {} offered", form.device,
                                    s.choice, caps.profiles.size()));
        out.profile = caps.profiles[static_cast<std::size_t>(s.choice)];
    }
    return out;
}

std::string settings_form_json(const DeviceSettingsForm& form) {
    nlohmann::json json = nlohmann::json::object();
    for (const DeviceSetting& s : form.settings) {
        if (s.kind == DeviceSettingKind::kNumber)
            json[s.key] = s.value;
        else if (s.choice >= 0 && s.choice < static_cast<int>(s.choices.size()))
            json[s.key] = s.choices[static_cast<std::size_t>(s.choice)];
    }
    return json.dump();
}

Expected<CameraPreview> camera_preview(const drivers::DeviceInfo& info,
                                       const std::vector<drivers::Frame>& frames,
                                       int max_width_px) {
    CameraPreview preview{.device = info.uri, .taken_at = std::chrono::system_clock::now()};
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const drivers::Frame& f = frames[i];
        const std::string name = fmt::format("{}#cam{}", info.uri, i + 1);
        if (f.format != drivers::PixelFormat::kGrey8 || f.width <= 0 || f.height <= 0 ||
            f.data.size() < f.stride_bytes * static_cast<std::size_t>(f.height))
            return fail(ErrorCode::kFormat, name + ": preview frame is not a whole grey8 image");
        const cv::Mat full(f.height, f.width, CV_8UC1, const_cast<std::uint8_t*>(f.data.data()),
                           f.stride_bytes);
        const double scale = std::min(1.0, static_cast<double>(max_width_px) / f.width);
        cv::Mat small;
        cv::resize(full, small,
                   cv::Size(std::max(1, static_cast<int>(std::lround(f.width * scale))),
                            std::max(1, static_cast<int>(std::lround(f.height * scale)))),
                   0, 0, cv::INTER_AREA);
        CameraImage image{.camera = name, .width_px = small.cols, .height_px = small.rows};
        image.grey.assign(small.datastart, small.dataend);  // continuous: freshly allocated
        preview.images.push_back(std::move(image));
    }
    return preview;
}

}  // namespace anascan::acquisition
