#pragma once
// The structured-light rig of the simulated scanner on the small scene, shared by the
// pattern tests and the triangulation tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/structured_light.hpp>
#include <optional>

#include "anascan/sim/structured_light_renderer.hpp"
#include "anascan/sim/viewpoints.hpp"
#include "sim_test_scenes.hpp"

namespace anascan::sim::sl_test {

// Cameras with the full rig's focal length but a small sensor crop: same pixel footprint
// on the stone as the 1600x1200 default, a fraction of the rendering time.
inline StructuredLightRigConfig narrow_rig() {
    return StructuredLightRigConfig{.camera_width_px = 240, .camera_height_px = 180};
}

class StructuredLightTest : public testing::SmallSceneSuite {
protected:
    static StructuredLightRig rig(const StructuredLightRigConfig& config, const Viewpoint& view) {
        const Eigen::Vector3d target = scene_->T_world_block.translation() +
                                       Eigen::Vector3d(0, 0, 0.5 * scene_->block_size_m.z());
        return make_structured_light_rig(config, sensor_looking_at(target, view));
    }
    static StructuredLightCapture render(const StructuredLightRig& r,
                                         const StructuredLightRenderConfig& config = {}) {
        return render_structured_light(*caster_, triangle_albedos(*scene_), r, config).value();
    }
};

// What the ray geometry says camera pixel (x, y) sees: the projector pixel coordinates of
// the surface point, or nothing when the projector does not light it.
inline std::optional<Eigen::Vector2d> lit_projector_xy(const RayCaster& caster,
                                                       const StructuredLightRig& rig,
                                                       const PinholeModel& cam, int x, int y) {
    const Eigen::Vector3d o = cam.T_world_device.translation(), d = cam.ray_world(x, y);
    const auto hit = caster.cast(o, d);
    if (!hit) return std::nullopt;
    const Eigen::Vector3d p = o + hit->distance_m * d;
    const Eigen::Vector3d uvz = rig.projector.project(p);
    const Eigen::Vector3d to_proj = rig.projector.T_world_device.translation() - p;
    if (uvz.z() <= 0 || uvz.x() < 0 || uvz.y() < 0 || uvz.x() > rig.projector.width_px - 1 ||
        uvz.y() > rig.projector.height_px - 1)
        return std::nullopt;
    if (caster.occluded(p, to_proj.normalized(), 1e-4, to_proj.norm() - 1e-4)) return std::nullopt;
    return Eigen::Vector2d(uvz.x(), uvz.y());
}

// Cosine between a surface normal and the direction to the projector.
inline double facing_projector(const StructuredLightRig& rig, const Eigen::Vector3d& p,
                               const Eigen::Vector3d& n) {
    return n.dot((rig.projector.T_world_device.translation() - p).normalized());
}

// Reference decode of one Gray-coded axis at a pixel (OpenCV layout, MSB first).
inline int decode_gray(const std::vector<cv::Mat>& images, int first, int bits, int x, int y) {
    int gray = 0;
    for (int k = 0; k < bits; ++k) {
        const int pattern = images[first + 2 * k].at<std::uint8_t>(y, x);
        const int inverse = images[first + 2 * k + 1].at<std::uint8_t>(y, x);
        gray = (gray << 1) | (pattern > inverse ? 1 : 0);
    }
    int binary = gray;
    for (int shift = 1; shift < bits; shift <<= 1) binary ^= binary >> shift;
    return binary;
}

}  // namespace anascan::sim::sl_test
