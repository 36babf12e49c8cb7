#include <cstdio>

#include "anascan/drivers/grey_image.hpp"
#include "anascan/sim/structured_light_renderer.hpp"

namespace anascan::sim {
namespace {

namespace fs = std::filesystem;

Expected<void> write_images(const fs::path& dir, const char* camera,
                            const std::vector<cv::Mat>& images) {
    for (std::size_t i = 0; i < images.size(); ++i) {
        char name[64];
        std::snprintf(name, sizeof(name), "pattern_%s_im%02zu.png", camera, i + 1);
        if (auto ok = drivers::write_grey_png(dir / name, images[i]); !ok) return ok;
    }
    return {};
}

}  // namespace

Expected<void> write_structured_light_capture(const fs::path& dir,
                                              const StructuredLightCapture& capture) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        return fail(ErrorCode::kIo, dir.string() + ": cannot create the folder: " + ec.message());
    if (auto ok = write_images(dir, "cam1", capture.cam1); !ok) return ok;
    if (auto ok = write_images(dir, "cam2", capture.cam2); !ok) return ok;
    return write_stereo_calibration(
        dir / "calibration.yml", capture.rig,
        drivers::sl::RecordedPatternLayout{.projector_width_px = capture.layout.width_px,
                                           .projector_height_px = capture.layout.height_px,
                                           .phase_steps = capture.layout.phase_steps,
                                           .phase_period_px = capture.layout.phase_period_px});
}

}  // namespace anascan::sim
