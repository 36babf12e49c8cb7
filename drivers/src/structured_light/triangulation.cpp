#include "anascan/drivers/structured_light/triangulation.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace anascan::drivers::sl {
namespace {

cv::Mat camera_matrix(const CameraIntrinsics& cam) {
    cv::Mat K(3, 3, CV_64F);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) K.at<double>(r, c) = cam.K(r, c);
    return K;
}

/// Normalised image coordinates (x/z, y/z) of distorted pixel positions.
std::vector<cv::Point2f> undistort(const std::vector<cv::Point2f>& px,
                                   const CameraIntrinsics& cam) {
    std::vector<cv::Point2f> out(px.size());
    const cv::Mat K = camera_matrix(cam);
    const cv::Mat dist(cam.distortion, true);
    constexpr std::size_t kBlock = 16384;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, px.size(), kBlock),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          const cv::Mat src(int(r.size()), 1, CV_32FC2,
                                            const_cast<cv::Point2f*>(px.data() + r.begin()));
                          cv::Mat dst(int(r.size()), 1, CV_32FC2, out.data() + r.begin());
                          cv::undistortPoints(src, dst, K, dist);
                      });
    return out;
}

}  // namespace

TriangulatedPoints triangulate_matches(const StereoMatches& matches,
                                       const StereoCalibration& calibration,
                                       const TriangulationConfig& config) {
    const std::size_t n = matches.cam1_px.size();
    std::vector<cv::Point2f> px1(n);
    for (std::size_t i = 0; i < n; ++i) px1[i] = cv::Point2f(matches.cam1_px[i]);
    const std::vector<cv::Point2f> ray1 = undistort(px1, calibration.cam1);
    const std::vector<cv::Point2f> ray2 = undistort(matches.cam2_px, calibration.cam2);
    TriangulatedPoints out{.position_m = std::vector<Eigen::Vector3f>(n),
                           .ray_gap_m = std::vector<float>(n),
                           .status = std::vector<PointStatus>(n)};
    const Eigen::Vector3d o2 = calibration.T_cam1_cam2.translation();
    const Eigen::Matrix3d R = calibration.T_cam1_cam2.linear();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16384),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); ++i) {
                              // Closest points of the rays s1 d1 and o2 + s2 d2 (cam1 frame).
                              const Eigen::Vector3d d1(ray1[i].x, ray1[i].y, 1.0);
                              const Eigen::Vector3d d2 =
                                  R * Eigen::Vector3d(ray2[i].x, ray2[i].y, 1.0);
                              const double a = d1.dot(d1), b = d1.dot(d2), c = d2.dot(d2);
                              const double d = -d1.dot(o2), e = -d2.dot(o2);
                              const double den = a * c - b * b;
                              if (den <= 1e-12 * a * c) {
                                  out.status[i] = PointStatus::kParallel;
                                  continue;
                              }
                              const double s1 = (b * e - c * d) / den;
                              const double s2 = (a * e - b * d) / den;
                              const Eigen::Vector3d p1 = s1 * d1;
                              const Eigen::Vector3d p2 = o2 + s2 * d2;
                              const Eigen::Vector3d mid = 0.5 * (p1 + p2);
                              out.position_m[i] = mid.cast<float>();
                              out.ray_gap_m[i] = float((p1 - p2).norm());
                              if (s1 <= 0.0 || s2 <= 0.0 || mid.z() < config.min_depth_m ||
                                  mid.z() > config.max_depth_m)
                                  out.status[i] = PointStatus::kDepth;
                              else if (out.ray_gap_m[i] > config.max_ray_gap_m)
                                  out.status[i] = PointStatus::kRayGap;
                              else
                                  out.status[i] = PointStatus::kOk;
                          }
                      });
    return out;
}

}  // namespace anascan::drivers::sl
