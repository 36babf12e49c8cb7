// libFuzzer harness for the structured-light calibration file (OpenCV FileStorage YAML or
// XML): the stereo calibration and the recorded pattern layout. Any input gives a checked
// calibration (finite, positive focal lengths, a rotation) or an error naming the file.
// OpenCV's parser runs uninstrumented: a finding inside it is reported against OpenCV.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "anascan/drivers/structured_light/stereo_calibration.hpp"

namespace {

namespace fs = std::filesystem;
using namespace anascan;
using namespace anascan::drivers::sl;

const fs::path& calibration_file() {
    static const fs::path file = fs::temp_directory_path() /
                                 ("anascan-fuzz-calibration-" + std::to_string(getpid()) + ".yml");
    return file;
}

template <typename T>
void require_named(const Expected<T>& result) {
    if (!result && result.error().message.find(calibration_file().string()) == std::string::npos)
        std::abort();
}

void check_camera(const CameraIntrinsics& camera) {
    if (!camera.K.allFinite() || !(camera.K(0, 0) > 0) || !(camera.K(1, 1) > 0)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::ofstream(calibration_file(), std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    const auto calibration = load_stereo_calibration(calibration_file(), {});
    require_named(calibration);
    if (calibration) {
        check_camera(calibration->cam1);
        check_camera(calibration->cam2);
        const Eigen::Matrix3d R = calibration->T_cam1_cam2.rotation();
        if (!calibration->T_cam1_cam2.matrix().allFinite() ||
            !(R.transpose() * R).isIdentity(1e-3) || !(std::abs(R.determinant() - 1) < 1e-3))
            std::abort();
    }
    require_named(load_pattern_layout(calibration_file()));
    return 0;
}
