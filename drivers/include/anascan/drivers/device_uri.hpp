#pragma once
/// \file
/// Device addresses as users type them: `sim:structured-light`, `sim:tof`,
/// `v4l2:/dev/video2`, `usb:VID:PID` (hexadecimal), `ptx:/path/to/station-exports`.
/// The backend registry chooses an implementation by `scheme` at run time.

#include <string>
#include <string_view>

#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

/// A parsed device address: `scheme:target`.
struct DeviceUri {
    std::string scheme;  ///< Backend family: "sim", "v4l2", "usb", "ptx".
    std::string target;  ///< Backend-specific: model name, device node, "VID:PID", folder.

    friend bool operator==(const DeviceUri&, const DeviceUri&) = default;
};

/// Parses `scheme:target`. The scheme is lower-case letters and digits; the target is not
/// empty; `usb:` targets must be two 4-digit hexadecimal numbers (`usb:1d6b:0104`).
Expected<DeviceUri> parse_device_uri(std::string_view text);

/// The text form, `scheme:target`.
std::string to_string(const DeviceUri& uri);

}  // namespace anascan::drivers
