// libFuzzer harness for the structured-light calibration file (OpenCV FileStorage YAML or
// XML): the stereo calibration and the recorded pattern layout, through the loaders users
// run. Any input gives a checked calibration (finite, positive focal lengths, a rotation) or
// an error naming the file.
//
// The loaders parse in a child process with a time limit and a crash boundary, so OpenCV
// 4.6's own hangs and crashes end in errors naming the file, not in findings, and the
// suite's short run cannot hang. libFuzzer sees no coverage from the child, so an input the
// child parsed to an end (a calibration or an ordinary error) is parsed again in this
// process (parse_stereo_calibration, parse_pattern_layout): there its coverage counts,
// ASan and UBSan watch anascan's reading code, and the result must equal the child's bit for
// bit. An input on which the child hit the time limit or crashed is not parsed here, where
// it would hang or crash the fuzzer on OpenCV's bug. The child's other endings are findings:
// a sanitizer report in the child ends it with a non-zero exit status. A null-pointer read
// in anascan's own code in the child would pass for one of OpenCV's crashes.
// OpenCV's parser runs uninstrumented: a finding inside it is reported against OpenCV.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "anascan/drivers/structured_light/stereo_calibration.hpp"
#include "structured_light/calibration_parse.hpp"

namespace {

namespace fs = std::filesystem;
using namespace anascan;
using namespace anascan::drivers::sl;

/// The parser's time limit here: an input on which OpenCV hangs costs the run this long, and
/// a valid file takes a few milliseconds under ASan. The unit tests cover the loaders'
/// default (kCalibrationParseTimeLimit).
constexpr std::chrono::milliseconds kParseTimeLimit{500};

const fs::path& calibration_file() {
    static const fs::path file = fs::temp_directory_path() /
                                 ("anascan-fuzz-calibration-" + std::to_string(getpid()) + ".yml");
    // Registered after `file` is made, so it runs before `file` is destroyed.
    static const bool removed_at_exit = (std::atexit([] {
                                             std::error_code ec;
                                             fs::remove(calibration_file(), ec);
                                         }),
                                         true);
    (void)removed_at_exit;
    return file;
}

bool says(const Error& error, const char* part) {
    return error.message.find(part) != std::string::npos;
}

/// Whether the loader's child stopped on a fault of OpenCV's parser: the time limit or a
/// signal.
template <typename T>
bool stopped_on_parser_fault(const Expected<T>& result) {
    return !result && (result.error().code == ErrorCode::kTimeout ||
                       says(result.error(), ": the calibration parser crashed (signal "));
}

/// Any other error of the child process is a finding: an exit status (a sanitizer report in
/// the child), a truncated or malformed result, no child started.
template <typename T>
void require_no_other_child_failure(const Expected<T>& result) {
    if (!result && !stopped_on_parser_fault(result) &&
        says(result.error(), ": the calibration parser "))
        std::abort();
}

template <typename T>
void require_named(const Expected<T>& result) {
    if (!result && result.error().message.find(calibration_file().string()) == std::string::npos)
        std::abort();
}

void check_camera(const CameraIntrinsics& camera) {
    if (!camera.K.allFinite() || !(camera.K(0, 0) > 0) || !(camera.K(1, 1) > 0)) std::abort();
}

void check_calibration(const StereoCalibration& calibration) {
    check_camera(calibration.cam1);
    check_camera(calibration.cam2);
    const Eigen::Matrix3d R = calibration.T_cam1_cam2.rotation();
    if (!calibration.T_cam1_cam2.matrix().allFinite() || !(R.transpose() * R).isIdentity(1e-3) ||
        !(std::abs(R.determinant() - 1) < 1e-3))
        std::abort();
}

bool same_bits(const double* a, const double* b, std::size_t n) {
    return n == 0 || std::memcmp(a, b, n * sizeof(double)) == 0;
}

bool same(const CameraIntrinsics& a, const CameraIntrinsics& b) {
    return same_bits(a.K.data(), b.K.data(), 9) && a.distortion.size() == b.distortion.size() &&
           same_bits(a.distortion.data(), b.distortion.data(), a.distortion.size()) &&
           a.width_px == b.width_px && a.height_px == b.height_px;
}

bool same(const StereoCalibration& a, const StereoCalibration& b) {
    return same(a.cam1, b.cam1) && same(a.cam2, b.cam2) &&
           same_bits(a.T_cam1_cam2.data(), b.T_cam1_cam2.data(), 16);
}

bool same(const std::optional<RecordedPatternLayout>& a,
          const std::optional<RecordedPatternLayout>& b) {
    if (!a || !b) return a.has_value() == b.has_value();
    return a->projector_width_px == b->projector_width_px &&
           a->projector_height_px == b->projector_height_px && a->phase_steps == b->phase_steps &&
           a->phase_period_px == b->phase_period_px;
}

/// The child's result and this process's must be the same value or the same error.
template <typename T>
void require_same(const Expected<T>& isolated, const Expected<T>& in_process) {
    if (isolated.has_value() != in_process.has_value()) std::abort();
    if (isolated && !same(*isolated, *in_process)) std::abort();
    if (!isolated && (isolated.error().code != in_process.error().code ||
                      isolated.error().message != in_process.error().message))
        std::abort();
}

/// Whether the parser came to an end (a calibration or an ordinary error).
bool fuzz_calibration_loader() {
    const auto calibration =
        load_stereo_calibration(calibration_file(), {.parse_time_limit = kParseTimeLimit});
    require_named(calibration);
    require_no_other_child_failure(calibration);
    if (calibration) check_calibration(*calibration);
    if (stopped_on_parser_fault(calibration)) return false;
    require_same(calibration, parse_stereo_calibration(calibration_file(), {}));
    return true;
}

void fuzz_layout_loader() {
    const auto layout =
        load_pattern_layout(calibration_file(), {.parse_time_limit = kParseTimeLimit});
    require_named(layout);
    require_no_other_child_failure(layout);
    if (!stopped_on_parser_fault(layout))
        require_same(layout, parse_pattern_layout(calibration_file()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::ofstream(calibration_file(), std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    // OpenCV parses the whole file when it opens it, for either loader: a file that stopped
    // the calibration's parser stops the layout's the same way, once more for nothing.
    if (fuzz_calibration_loader()) fuzz_layout_loader();
    return 0;
}
