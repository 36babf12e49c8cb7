#pragma once
/// \file
/// Calibration of a two-camera structured-light scanner, read from OpenCV FileStorage YAML
/// (the keys written by OpenCV's stereo calibration samples: cam1_intrinsics,
/// cam1_distorsion, cam1_size, cam2_..., R, T).
///
/// OpenCV 4.6's FileStorage parsers can loop for ever or crash on a malformed file, so both
/// loaders run OpenCV in a child process, with a time limit (kCalibrationParseTimeLimit) and
/// a crash boundary: such a file ends in an error naming it, never a hung or crashed caller.
/// Thread-safe: each load forks its own child.

#include <Eigen/Core>
#include <chrono>
#include <filesystem>
#include <optional>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/pose.hpp"

namespace anascan::drivers::sl {

/// Pinhole camera with OpenCV's distortion model.
struct CameraIntrinsics {
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity();  ///< Camera matrix, pixels.
    std::vector<double> distortion;  ///< OpenCV order: k1 k2 p1 p2 [k3 [k4 k5 k6]]; may be empty.
    int width_px = 0;                ///< Image size the calibration belongs to.
    int height_px = 0;
};

/// Both cameras, labelled like the image sequences they belong to (cam1 = the `--cam1`
/// images). The reconstruction frame is cam1's: x right, y down, z forward, metres.
struct StereoCalibration {
    CameraIntrinsics cam1;
    CameraIntrinsics cam2;
    Pose T_cam1_cam2 = Pose::Identity();  ///< X_cam1 = T_cam1_cam2 * X_cam2, metres.
};

/// How long OpenCV may parse a calibration file before the load gives up with kTimeout. A
/// valid file takes milliseconds, also under a sanitizer; a few seconds leave room for a
/// loaded machine and stay well under the fuzzers' own 10 s limit.
inline constexpr std::chrono::milliseconds kCalibrationParseTimeLimit{3000};

/// How to read a calibration file.
struct StereoCalibrationLoadConfig {
    /// The file's "cam1" is the camera of the cam2 images and vice versa (true for the
    /// GSoC 2015 statue data set, see docs/structured-light.md). Without the swap the file
    /// follows OpenCV's stereoCalibrate convention X_cam2 = R * X_cam1 + T.
    bool swap_cameras = false;
    /// Length of one unit of the file's T, metres (calibration boards in mm: 1e-3).
    double file_unit_m = 1e-3;
    /// How long OpenCV's parser may run in the child process.
    std::chrono::milliseconds parse_time_limit = kCalibrationParseTimeLimit;
};

/// Reads and checks a calibration (3x3 matrices, positive focal lengths, a rotation R,
/// image sizes). Errors name the file and the key; a parser that does not finish within
/// `config.parse_time_limit` gives kTimeout, one that crashes kFormat ("the calibration
/// parser crashed (signal SIGSEGV) on this file"); kIo when no child process can be started.
Expected<StereoCalibration> load_stereo_calibration(const std::filesystem::path& path,
                                                    const StereoCalibrationLoadConfig& config);

/// The pattern layout a calibration file may record next to the cameras (the simulator
/// writes it): `proj_size` [w, h], `pattern_phase_steps`, `pattern_phase_period_px`.
struct RecordedPatternLayout {
    int projector_width_px = 0;
    int projector_height_px = 0;
    int phase_steps = 0;  ///< 0: Gray code only.
    int phase_period_px = 0;
};

/// How to read the pattern layout of a calibration file.
struct PatternLayoutLoadConfig {
    /// How long OpenCV's parser may run in the child process.
    std::chrono::milliseconds parse_time_limit = kCalibrationParseTimeLimit;
};

/// Reads the recorded layout; empty when the file has no `proj_size`. kFormat naming the
/// file and key for a malformed entry, kIo when the file is missing; a parser that hangs or
/// crashes as for load_stereo_calibration.
Expected<std::optional<RecordedPatternLayout>> load_pattern_layout(
    const std::filesystem::path& path, const PatternLayoutLoadConfig& config = {});

}  // namespace anascan::drivers::sl
