#include "sl_reference.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/structured_light.hpp>
#include <random>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan::test {
namespace {

struct Rectification {
    cv::Mat map1x, map1y, map2x, map2y, Q;
};

bool read_rectification(const std::filesystem::path& file, Rectification& r) {
    cv::FileStorage fs(file.string(), cv::FileStorage::READ);
    if (!fs.isOpened()) return false;
    cv::Mat K1, D1, K2, D2, R1, R2, P1, P2;
    fs["cam1_intrinsics"] >> K1;
    fs["cam1_distorsion"] >> D1;
    fs["cam2_intrinsics"] >> K2;
    fs["cam2_distorsion"] >> D2;
    fs["R1"] >> R1;
    fs["R2"] >> R2;
    fs["P1"] >> P1;
    fs["P2"] >> P2;
    fs["Q"] >> r.Q;
    const cv::FileNode size = fs["cam1_size"];
    if (K1.empty() || K2.empty() || R1.empty() || P1.empty() || r.Q.empty() || size.size() != 2)
        return false;
    const cv::Size image{int(size[0]), int(size[1])};
    cv::initUndistortRectifyMap(K1, D1, R1, P1, image, CV_32FC1, r.map1x, r.map1y);
    cv::initUndistortRectifyMap(K2, D2, R2, P2, image, CV_32FC1, r.map2x, r.map2y);
    return true;
}

cv::Mat load_rectified(const std::filesystem::path& file, const cv::Mat& mx, const cv::Mat& my) {
    const cv::Mat im = cv::imread(file.string(), cv::IMREAD_GRAYSCALE);
    if (im.empty()) return im;
    cv::Mat out;
    cv::remap(im, out, mx, my, cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar());
    return out;
}

}  // namespace

namespace {

// The decoder's inputs, loaded and rectified as the sample does: the cam1 images with the
// file's cam2 maps and vice versa. Empty `error` when all images load.
struct GrayCodeImages {
    std::vector<std::vector<cv::Mat>> pattern;
    std::vector<cv::Mat> white{2}, black{2};
    std::string error;
};

GrayCodeImages load_images(const Rectification& rect,
                           const std::vector<std::filesystem::path>& cam1_files,
                           const std::vector<std::filesystem::path>& cam2_files, std::size_t n) {
    GrayCodeImages in;
    in.pattern.assign(2, std::vector<cv::Mat>(n));
    for (std::size_t i = 0; i < n + 2; ++i) {
        const cv::Mat a = load_rectified(cam1_files[i], rect.map2x, rect.map2y);
        const cv::Mat b = load_rectified(cam2_files[i], rect.map1x, rect.map1y);
        if (a.empty() || b.empty()) {
            in.error = "unreadable image " + std::to_string(i + 1);
            return in;
        }
        if (i < n)
            in.pattern[0][i] = a, in.pattern[1][i] = b;
        else if (i == n)
            in.white[0] = a, in.white[1] = b;
        else
            in.black[0] = a, in.black[1] = b;
    }
    return in;
}

// The finite points of the disparity map, millimetres to metres.
void reproject(cv::Mat disparity, const cv::Mat& Q, PointCloud& cloud) {
    cv::Mat points;
    disparity.convertTo(disparity, CV_32FC1);
    cv::reprojectImageTo3D(disparity, points, Q, true, -1);
    for (int y = 0; y < points.rows; ++y) {
        for (int x = 0; x < points.cols; ++x) {
            const cv::Vec3f p = points.at<cv::Vec3f>(y, x);
            if (disparity.at<float>(y, x) == 0.0f || !std::isfinite(p[2]) || std::abs(p[2]) >= 1e4f)
                continue;
            cloud.positions.emplace_back(p[0] * 1e-3f, p[1] * 1e-3f, p[2] * 1e-3f);
        }
    }
}

}  // namespace

OpenCvGrayCodeResult run_opencv_graycode(const std::filesystem::path& calibration,
                                         const std::vector<std::filesystem::path>& cam1_files,
                                         const std::vector<std::filesystem::path>& cam2_files,
                                         int projector_width_px, int projector_height_px) {
    OpenCvGrayCodeResult result;
    const Stopwatch total;
    Rectification rect;
    if (!read_rectification(calibration, rect)) {
        result.error = "cannot read " + calibration.string();
        return result;
    }
    cv::structured_light::GrayCodePattern::Params params;
    params.width = projector_width_px;
    params.height = projector_height_px;
    const auto graycode = cv::structured_light::GrayCodePattern::create(params);
    const std::size_t n = graycode->getNumberOfPatternImages();
    if (cam1_files.size() != n + 2 || cam2_files.size() != n + 2) {
        result.error = "wrong image count";
        return result;
    }
    GrayCodeImages in = load_images(rect, cam1_files, cam2_files, n);
    if (!in.error.empty()) {
        result.error = in.error;
        return result;
    }
    result.load_s = total.seconds();
    cv::Mat disparity;
    const Stopwatch decode;
    if (!graycode->decode(in.pattern, disparity, in.black, in.white,
                          cv::structured_light::DECODE_3D_UNDERWORLD)) {
        result.error = "GrayCodePattern::decode failed";
        return result;
    }
    result.decode_s = decode.seconds();
    reproject(disparity, rect.Q, result.cloud);
    result.total_s = total.seconds();
    result.ok = true;
    return result;
}

double median_local_noise_m(const PointCloud& cloud, int k, std::size_t samples) {
    if (cloud.size() <= std::size_t(k)) return 0.0;
    const KdTree tree(cloud.positions);
    std::mt19937 rng(42);
    std::uniform_int_distribution<std::size_t> pick(0, cloud.size() - 1);
    std::vector<double> distances;
    std::vector<Neighbor> nn;
    for (std::size_t s = 0; s < samples; ++s) {
        const Eigen::Vector3f& q = cloud.positions[pick(rng)];
        tree.knn(q, std::size_t(k) + 1, nn);  // The first is the point itself.
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (std::size_t i = 1; i < nn.size(); ++i)
            mean += cloud.positions[nn[i].index].cast<double>();
        mean /= double(nn.size() - 1);
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (std::size_t i = 1; i < nn.size(); ++i) {
            const Eigen::Vector3d d = cloud.positions[nn[i].index].cast<double>() - mean;
            cov += d * d.transpose();
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
        const Eigen::Vector3d normal = eig.eigenvectors().col(0);
        distances.push_back(std::abs(normal.dot(q.cast<double>() - mean)));
    }
    auto mid = distances.begin() + std::ptrdiff_t(distances.size() / 2);
    std::nth_element(distances.begin(), mid, distances.end());
    return *mid;
}

}  // namespace anascan::test
