#include "sl_synthetic.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/core.hpp>

namespace anascan::test {

SyntheticRig make_rig() {
    SyntheticRig rig;
    drivers::sl::CameraIntrinsics cam;
    cam.K << 800.0, 0.0, 320.0, 0.0, 800.0, 240.0, 0.0, 0.0, 1.0;
    cam.width_px = 640;
    cam.height_px = 480;
    rig.calibration.cam1 = cam;
    rig.calibration.cam2 = cam;
    // cam2 0.2 m to the right, turned 10 degrees towards cam1's axis.
    rig.calibration.T_cam1_cam2 = Eigen::Translation3d(0.2, 0.0, 0.0) *
                                  Eigen::AngleAxisd(-10.0 * M_PI / 180.0, Eigen::Vector3d::UnitY());
    rig.projector_K << 400.0, 0.0, 159.5, 0.0, 400.0, 99.5, 0.0, 0.0, 1.0;
    rig.T_cam1_projector = Eigen::Translation3d(0.1, 0.01, 0.0) *
                           Eigen::AngleAxisd(-5.0 * M_PI / 180.0, Eigen::Vector3d::UnitY());
    rig.plane_normal = Eigen::Vector3d(0.15, -0.1, 1.0).normalized();
    rig.plane_offset_m = 1.0;
    return rig;
}

Eigen::Vector3d surface_point(const SyntheticRig& rig, int camera, double x, double y) {
    const auto& cam = camera == 1 ? rig.calibration.cam1 : rig.calibration.cam2;
    const Pose T = camera == 1 ? Pose::Identity() : rig.calibration.T_cam1_cam2;
    const Eigen::Vector3d d = T.linear() * (cam.K.inverse() * Eigen::Vector3d(x, y, 1.0));
    const Eigen::Vector3d o = T.translation();
    const double s = (rig.plane_offset_m - rig.plane_normal.dot(o)) / rig.plane_normal.dot(d);
    return o + s * d;
}

Eigen::Vector2d projector_coordinates(const SyntheticRig& rig, int camera, double x, double y) {
    const Eigen::Vector3d p = rig.T_cam1_projector.inverse() * surface_point(rig, camera, x, y);
    const Eigen::Vector3d uvw = rig.projector_K * p;
    return uvw.head<2>() / uvw.z();
}

namespace {

double sample(const cv::Mat& pattern, const Eigen::Vector2d& uv, bool bilinear) {
    const auto at = [&](int u, int v) {
        if (u < 0 || v < 0 || u >= pattern.cols || v >= pattern.rows) return 0.0;
        return double(pattern.at<std::uint8_t>(v, u));
    };
    if (!bilinear) return at(int(std::floor(uv.x() + 0.5)), int(std::floor(uv.y() + 0.5)));
    const int u0 = int(std::floor(uv.x())), v0 = int(std::floor(uv.y()));
    const double fu = uv.x() - u0, fv = uv.y() - v0;
    return (1 - fv) * ((1 - fu) * at(u0, v0) + fu * at(u0 + 1, v0)) +
           fv * ((1 - fu) * at(u0, v0 + 1) + fu * at(u0 + 1, v0 + 1));
}

}  // namespace

std::vector<cv::Mat> render(const SyntheticRig& rig, int camera,
                            const std::vector<cv::Mat>& patterns, const RenderOptions& options) {
    const int w = rig.calibration.cam1.width_px, h = rig.calibration.cam1.height_px;
    const int s = options.supersample;
    // Projector coordinates of every sample, computed once for all patterns.
    std::vector<Eigen::Vector2d> uv(std::size_t(w) * h * s * s);
    tbb::parallel_for(0, h, [&](int y) {
        for (int x = 0; x < w; ++x)
            for (int j = 0; j < s; ++j)
                for (int i = 0; i < s; ++i)
                    uv[((std::size_t(y) * w + x) * s + j) * s + i] = projector_coordinates(
                        rig, camera, x + (i + 0.5) / s - 0.5, y + (j + 0.5) / s - 0.5);
    });
    std::vector<cv::Mat> images;
    for (const cv::Mat& pattern : patterns) {
        cv::Mat im(h, w, CV_8UC1);
        tbb::parallel_for(0, h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                double sum = 0.0;
                for (int k = 0; k < s * s; ++k)
                    sum +=
                        sample(pattern, uv[(std::size_t(y) * w + x) * s * s + k], options.bilinear);
                im.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(
                    options.black + options.gain * sum / (255.0 * s * s));
            }
        });
        images.push_back(im);
    }
    return images;
}

}  // namespace anascan::test
