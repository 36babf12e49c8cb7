#pragma once
/// \file
/// What a device can do (capabilities) and what it is asked to do (settings), typed and
/// validated: an invalid setting is an error value (kInvalidArgument) naming the setting,
/// the value, the allowed range and the device.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/drivers/frame.hpp"
#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

/// A closed interval [min, max] of a numeric setting.
struct NumericRange {
    double min = 0.0;
    double max = 0.0;
    bool contains(double v) const { return v >= min && v <= max; }
};

/// One image stream a camera can deliver.
struct StreamProfile {
    int width = 0;
    int height = 0;
    PixelFormat format = PixelFormat::kGrey8;
    double frame_rate_hz = 0.0;  ///< 0 when the device does not say.
    friend bool operator==(const StreamProfile&, const StreamProfile&) = default;
};

/// What a device offers. An absent range means the setting does not exist on the device.
struct Capabilities {
    bool can_stream = false;        ///< A camera: start/stop with frame callbacks.
    bool can_capture_scan = false;  ///< A scanner: one-shot capture_scan().
    std::vector<StreamProfile> profiles;
    std::optional<NumericRange> exposure_us;           ///< Exposure time, microseconds.
    std::optional<NumericRange> gain;                  ///< Analogue gain, device units.
    std::optional<NumericRange> angular_step_deg;      ///< Scanner angular resolution, degrees.
    std::optional<NumericRange> range_m;               ///< Scanner measurable range, metres.
    std::optional<NumericRange> horizontal_field_deg;  ///< Scanner sweep width, degrees.
    std::optional<NumericRange> vertical_field_deg;    ///< Scanner sweep height, degrees.
};

/// Requested or current settings; an empty field means "leave as it is".
struct DeviceSettings {
    std::optional<StreamProfile> profile;    ///< Camera stream (size, format, rate).
    std::optional<double> exposure_us;       ///< Microseconds.
    std::optional<double> gain;              ///< Device units.
    std::optional<double> angular_step_deg;  ///< Degrees.
    std::optional<double> min_range_m;       ///< Metres; with max_range_m within range_m.
    std::optional<double> max_range_m;       ///< Metres.
    /// Sweep of a scanning device (ToF): width in azimuth, height in elevation, degrees.
    std::optional<double> horizontal_field_deg;
    std::optional<double> vertical_field_deg;
    friend bool operator==(const DeviceSettings&, const DeviceSettings&) = default;
};

/// Checks every present field against `caps`; the first violation is returned as
/// kInvalidArgument: "v4l2:/dev/video2: exposure_us 5e+06 outside [10, 100000]".
Expected<void> validate_settings(const DeviceSettings& requested, const Capabilities& caps,
                                 std::string_view device_name);

/// `current` with every field present in `requested` replaced.
DeviceSettings merge_settings(DeviceSettings current, const DeviceSettings& requested);

/// JSON text of the present fields (for recordings and ScanMetadata::settings_json).
std::string settings_to_json(const DeviceSettings& settings);

/// Parses `settings_to_json` output; kFormat on malformed text, naming `source`.
Expected<DeviceSettings> settings_from_json(std::string_view json, std::string_view source);

}  // namespace anascan::drivers
