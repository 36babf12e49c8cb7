#include "anascan/drivers/device_uri.hpp"

#include <algorithm>
#include <cctype>

namespace anascan::drivers {
namespace {

bool is_scheme_char(char c) {
    return std::islower(static_cast<unsigned char>(c)) ||
           std::isdigit(static_cast<unsigned char>(c));
}

bool is_hex4(std::string_view s) {
    return s.size() == 4 && std::all_of(s.begin(), s.end(), [](char c) {
               return std::isxdigit(static_cast<unsigned char>(c)) != 0;
           });
}

Expected<void> check_usb_target(std::string_view text, std::string_view target) {
    const std::size_t colon = target.find(':');
    if (colon == std::string_view::npos || !is_hex4(target.substr(0, colon)) ||
        !is_hex4(target.substr(colon + 1))) {
        return fail(ErrorCode::kInvalidArgument,
                    "device '" + std::string(text) +
                        "': a USB device is written usb:VID:PID with 4 hex digits each, "
                        "e.g. usb:1d6b:0104");
    }
    return {};
}

}  // namespace

Expected<DeviceUri> parse_device_uri(std::string_view text) {
    const std::size_t colon = text.find(':');
    if (colon == std::string_view::npos || colon == 0 || colon + 1 == text.size()) {
        return fail(ErrorCode::kInvalidArgument,
                    "device '" + std::string(text) +
                        "': expected SCHEME:TARGET, e.g. sim:structured-light, "
                        "v4l2:/dev/video2, usb:1d6b:0104");
    }
    DeviceUri uri{std::string(text.substr(0, colon)), std::string(text.substr(colon + 1))};
    if (!std::all_of(uri.scheme.begin(), uri.scheme.end(), is_scheme_char)) {
        return fail(ErrorCode::kInvalidArgument, "device '" + std::string(text) +
                                                     "': the scheme '" + uri.scheme +
                                                     "' must be lower-case letters and digits");
    }
    if (uri.scheme == "usb") {
        if (auto ok = check_usb_target(text, uri.target); !ok) return fail(ok.error());
    }
    return uri;
}

std::string to_string(const DeviceUri& uri) { return uri.scheme + ":" + uri.target; }

}  // namespace anascan::drivers
