#include "anascan/sim/structured_light_rig.hpp"

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>

namespace anascan::sim {
namespace {

PinholeModel pinhole(int width, int height, double focal_px, const Pose& T_world_device) {
    return PinholeModel{.width_px = width,
                        .height_px = height,
                        .fx_px = focal_px,
                        .fy_px = focal_px,
                        .cx_px = 0.5 * (width - 1),
                        .cy_px = 0.5 * (height - 1),
                        .T_world_device = T_world_device};
}

cv::Mat intrinsics(const PinholeModel& m) {
    return (cv::Mat_<double>(3, 3) << m.fx_px, 0, m.cx_px, 0, m.fy_px, m.cy_px, 0, 0, 1);
}

cv::Mat to_cv(const Eigen::MatrixXd& m) {
    cv::Mat out;
    cv::eigen2cv(m, out);
    return out;
}

}  // namespace

Eigen::Vector3d PinholeModel::ray_world(double x_px, double y_px) const {
    const Eigen::Vector3d d((x_px - cx_px) / fx_px, (y_px - cy_px) / fy_px, 1.0);
    return T_world_device.linear() * d.normalized();
}

Eigen::Vector3d PinholeModel::project(const Eigen::Vector3d& p_world) const {
    const Eigen::Vector3d p = T_world_device.inverse() * p_world;
    return {fx_px * p.x() / p.z() + cx_px, fy_px * p.y() / p.z() + cy_px, p.z()};
}

StructuredLightRig make_structured_light_rig(const StructuredLightRigConfig& c,
                                             const Pose& T_world_rig) {
    const Eigen::Vector3d meet(0.0, 0.0, c.working_distance_m);  // Rig (projector) frame.
    // Rig frame: x right, y down; cameras on the x axis, verging on `meet` with rig y down.
    auto camera_pose = [&](double x_m) {
        return T_world_rig * look_at(Eigen::Vector3d(x_m, 0, 0), meet, -Eigen::Vector3d::UnitY());
    };
    return StructuredLightRig{.projector = pinhole(c.projector_width_px, c.projector_height_px,
                                                   c.projector_focal_px, T_world_rig),
                              .cam1 = pinhole(c.camera_width_px, c.camera_height_px,
                                              c.camera_focal_px, camera_pose(-0.5 * c.baseline_m)),
                              .cam2 = pinhole(c.camera_width_px, c.camera_height_px,
                                              c.camera_focal_px, camera_pose(0.5 * c.baseline_m))};
}

drivers::sl::StereoCalibration stereo_calibration(const StructuredLightRig& rig) {
    auto camera = [](const PinholeModel& m) {
        drivers::sl::CameraIntrinsics c{.width_px = m.width_px, .height_px = m.height_px};
        c.K << m.fx_px, 0, m.cx_px, 0, m.fy_px, m.cy_px, 0, 0, 1;
        return c;
    };
    return {.cam1 = camera(rig.cam1),
            .cam2 = camera(rig.cam2),
            .T_cam1_cam2 = rig.cam1.T_world_device.inverse() * rig.cam2.T_world_device};
}

Expected<void> write_stereo_calibration(
    const std::filesystem::path& path, const StructuredLightRig& rig,
    const std::optional<drivers::sl::RecordedPatternLayout>& layout) {
    const Pose T_cam2_cam1 = rig.cam2.T_world_device.inverse() * rig.cam1.T_world_device;
    const cv::Mat K1 = intrinsics(rig.cam1), K2 = intrinsics(rig.cam2);
    const cv::Mat dist = cv::Mat::zeros(1, 5, CV_64F);
    const cv::Mat R = to_cv(T_cam2_cam1.linear());
    const cv::Mat T = to_cv(1000.0 * T_cam2_cam1.translation());
    Eigen::Matrix4d RT = T_cam2_cam1.matrix();
    RT.block<3, 1>(0, 3) *= 1000.0;
    const cv::Size size(rig.cam1.width_px, rig.cam1.height_px);
    cv::Mat R1, R2, P1, P2, Q;
    cv::stereoRectify(K1, dist, K2, dist, size, R, T, R1, R2, P1, P2, Q);
    const std::filesystem::path folder = path.parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder))
        return fail(ErrorCode::kIo, path.string() + ": cannot write, no folder " + folder.string());
    cv::FileStorage fs;
    try {
        if (!fs.open(path.string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML))
            return fail(ErrorCode::kIo, path.string() + ": cannot open for writing");
    } catch (const cv::Exception& e) {
        return fail(ErrorCode::kIo, path.string() + ": cannot open for writing: " + e.what());
    }
    fs << "cam1_intrinsics" << K1 << "cam1_distorsion" << dist << "cam1_size" << size;
    fs << "cam2_intrinsics" << K2 << "cam2_distorsion" << dist << "cam2_size" << size;
    fs << "RT_cam1_2_cam2" << to_cv(RT) << "R" << R << "T" << T << "stereo_error" << 0.0;
    fs << "Q" << Q << "R1" << R1 << "R2" << R2 << "P1" << P1 << "P2" << P2;
    fs << "proj_intrinsics" << intrinsics(rig.projector) << "proj_size"
       << cv::Size(rig.projector.width_px, rig.projector.height_px);
    fs << "T_world_cam1_m" << to_cv(rig.cam1.T_world_device.matrix()) << "T_world_proj_m"
       << to_cv(rig.projector.T_world_device.matrix());
    if (layout)
        fs << "pattern_phase_steps" << layout->phase_steps << "pattern_phase_period_px"
           << layout->phase_period_px;
    fs.release();
    return {};
}

}  // namespace anascan::sim
