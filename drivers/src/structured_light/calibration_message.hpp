#pragma once
// The result of reading a calibration file, as the isolated parser's child sends it to its
// parent (byte_message.hpp: this machine's own layout, never stored).

#include <optional>
#include <string>
#include <string_view>

#include "anascan/drivers/structured_light/stereo_calibration.hpp"

namespace anascan::drivers::sl {

/// The message for a result: its error (code and message) or its values.
std::string encode_result(const Expected<StereoCalibration>& result);
std::string encode_result(const Expected<std::optional<RecordedPatternLayout>>& result);

/// The result a message carries; kFormat naming `file` when `bytes` is not such a message.
Expected<StereoCalibration> decode_stereo_calibration(std::string_view bytes,
                                                      const std::string& file);
Expected<std::optional<RecordedPatternLayout>> decode_pattern_layout(std::string_view bytes,
                                                                     const std::string& file);

}  // namespace anascan::drivers::sl
