#pragma once
// The calibration file read in this process: what the isolated loaders of
// stereo_calibration.hpp run in their child process.

#include <filesystem>
#include <optional>

#include "anascan/drivers/structured_light/stereo_calibration.hpp"

namespace anascan::drivers::sl {

/// load_stereo_calibration without the child process: the same checks and the same result,
/// but OpenCV's parser runs in the caller's process, where a malformed file can make it
/// never return or crash. For the child, and for a fuzzer under its own time limit.
Expected<StereoCalibration> parse_stereo_calibration(const std::filesystem::path& path,
                                                     const StereoCalibrationLoadConfig& config);

/// load_pattern_layout without the child process (see parse_stereo_calibration).
Expected<std::optional<RecordedPatternLayout>> parse_pattern_layout(
    const std::filesystem::path& path);

}  // namespace anascan::drivers::sl
