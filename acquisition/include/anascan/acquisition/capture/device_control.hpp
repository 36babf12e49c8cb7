#pragma once
/// \file
/// The session's device as the operator sees it between captures: its settings as a form
/// (numbers with units and ranges, choices) and the latest images of its cameras (the
/// structured-light scanner's two cameras). acquisition's own types: the GUI sees no driver
/// header. CaptureSession::device_settings / apply_device_settings / preview_cameras run
/// on the session's scanner thread, so never during a capture.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace anascan::acquisition {

enum class DeviceSettingKind {
    kNumber,  ///< value within [min, max], in `unit`.
    kChoice,  ///< one of `choices` (a camera's stream profiles).
};

/// One setting of the device.
struct DeviceSetting {
    std::string key;    ///< The drivers' name: "exposure_us", "max_range_m", "profile", ...
    std::string label;  ///< "Exposure", "Farthest depth", ...
    std::string unit;   ///< "µs", "m", "°", or empty.
    DeviceSettingKind kind = DeviceSettingKind::kNumber;
    double min = 0.0;  ///< kNumber: the device's allowed range, in `unit`.
    double max = 0.0;
    double value = 0.0;                ///< kNumber: in `unit`.
    std::vector<std::string> choices;  ///< kChoice: "640 x 480 grey8 30 Hz", ...
    int choice = -1;                   ///< kChoice: index into choices.
    friend bool operator==(const DeviceSetting&, const DeviceSetting&) = default;
};

/// Every setting the device has, in effect (read) or asked for (edited).
struct DeviceSettingsForm {
    std::string device;  ///< The device's URI.
    std::vector<DeviceSetting> settings;
    friend bool operator==(const DeviceSettingsForm&, const DeviceSettingsForm&) = default;
};

/// The form's values as JSON text ({"exposure_us": 10000, ...}; choices by their text), as
/// the session records applied settings.
std::string settings_form_json(const DeviceSettingsForm& form);

/// One camera's image, grey, downscaled.
struct CameraImage {
    std::string camera;  ///< "cam1 (sim:structured-light/small-block#cam1)".
    int width_px = 0;
    int height_px = 0;
    std::vector<std::uint8_t> grey;  ///< width_px * height_px bytes, row by row.
};

/// What the device's cameras saw at one moment (empty images: a scanner without cameras).
struct CameraPreview {
    std::string device;
    std::chrono::system_clock::time_point taken_at{};
    std::vector<CameraImage> images;  ///< cam1, cam2 for a structured-light scanner.
};

}  // namespace anascan::acquisition
