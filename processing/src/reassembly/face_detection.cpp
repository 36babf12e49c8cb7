// Planar faces: CGAL Efficient RANSAC on a subsample, every input point assigned to the
// best plane, planes refitted by least squares, parallel close planes merged, curved strips
// dropped, and each face's normal taken from its best-fitting half.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "anascan/processing/core/median.hpp"
#include "cgal_geometry.hpp"
#include "feature_steps.hpp"

namespace anascan::reassembly::detail {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

std::vector<std::size_t> stride_sample(std::size_t n, std::size_t max_count) {
    const std::size_t stride = std::max<std::size_t>(1, (n + max_count - 1) / max_count);
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < n; i += stride) out.push_back(i);
    return out;
}

// The least-squares plane normal of `pts` (unit, sign arbitrary).
Eigen::Vector3d least_squares_normal(const std::vector<Eigen::Vector3d>& pts) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : pts) mean += p;
    mean /= double(pts.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3d& p : pts) cov += (p - mean) * (p - mean).transpose();
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0);
}

// The median squared distance of `pts` to the plane through `on` with `normal`.
double median_squared_distance(const std::vector<Eigen::Vector3d>& pts,
                               const Eigen::Vector3d& normal, const Eigen::Vector3d& on) {
    std::vector<double> sq(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) sq[k] = std::pow(normal.dot(pts[k] - on), 2);
    const auto mid = sq.begin() + std::ptrdiff_t(sq.size() / 2);
    std::nth_element(sq.begin(), mid, sq.end());
    return *mid;
}

// The normal of the face's best-fitting half (least median of squares: of planes through
// three inliers drawn evenly, the one whose median squared distance over a sample is
// least), refitted by least squares on the points within 2.5 robust deviations of it. The
// dressed surface is the face's largest flat part: erosion, a chipped or recessed panel on
// one side tilt a fit through every inlier (docs/reassembly.md, "Face planes").
Eigen::Vector3d least_median_normal(const FeatureInput& in, const std::vector<std::size_t>& inliers,
                                    const Eigen::Vector3d& n) {
    constexpr std::size_t kSample = 2000, kDraws = 300;
    if (inliers.size() < 20) return n;
    const std::vector<std::size_t> sample = stride_sample(inliers.size(), kSample);
    std::vector<Eigen::Vector3d> pts;
    for (std::size_t j : sample) pts.push_back(in.points[inliers[j]].cast<double>());
    Eigen::Vector3d best_n = n, best_on = pts[0];
    double best = median_squared_distance(pts, n, pts[pts.size() / 2]);
    // Deterministic draws: a multiplicative hash of the draw index picks the three points.
    for (std::size_t t = 0; t < kDraws; ++t) {
        const std::size_t m = pts.size();
        const std::size_t a = (t * 2654435761u) % m, b = (t * 40503u + m / 3) % m,
                          c = (t * 9973u + 2 * m / 3) % m;
        Eigen::Vector3d normal = (pts[b] - pts[a]).cross(pts[c] - pts[a]);
        if (normal.norm() < 1e-12) continue;
        normal.normalize();
        if (normal.dot(n) < std::cos(10.0 * kDegToRad) &&
            -normal.dot(n) < std::cos(10.0 * kDegToRad))
            continue;
        if (normal.dot(n) < 0.0) normal = -normal;
        const double value = median_squared_distance(pts, normal, pts[a]);
        if (value < best) best = value, best_n = normal, best_on = pts[a];
    }
    // Least squares on the points near the best half (robust scale 1.4826 · median).
    const double band = 2.5 * 1.4826 * std::sqrt(best) + 1e-9;
    std::vector<Eigen::Vector3d> near;
    for (std::size_t i : inliers) {
        const Eigen::Vector3d p = in.points[i].cast<double>();
        if (std::abs(best_n.dot(p - best_on)) <= band) near.push_back(p);
    }
    if (near.size() < 3) return best_n;
    const Eigen::Vector3d refit = least_squares_normal(near);
    return refit.dot(n) < 0.0 ? Eigen::Vector3d(-refit) : refit;
}

// The face's plane along normal n: the dressed surface is the outer envelope (tool marks,
// a recessed centre and carving lie below it), so the offset is the 95th percentile of the
// inliers' heights.
void set_plane(const FeatureInput& in, FaceBuild& f, const Eigen::Vector3d& n) {
    f.face.normal = n;
    std::vector<double> heights;
    heights.reserve(f.inliers.size());
    for (std::size_t i : f.inliers) heights.push_back(n.dot(in.points[i].cast<double>()));
    const auto k = heights.begin() + std::ptrdiff_t(0.95 * double(heights.size() - 1));
    std::nth_element(heights.begin(), k, heights.end());
    f.face.offset_m = *k;
}

// Least-squares plane of the inliers (double, relative to their centroid); the normal
// keeps the side of `like`.
void refit_plane(const FeatureInput& in, FaceBuild& f, const Eigen::Vector3d& like) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t i : f.inliers) mean += in.points[i].cast<double>();
    mean /= double(f.inliers.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::size_t i : f.inliers) {
        const Eigen::Vector3d d = in.points[i].cast<double>() - mean;
        cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    Eigen::Vector3d n = eig.eigenvectors().col(0);
    if (n.dot(like) < 0.0) n = -n;
    set_plane(in, f, n);
    f.face.num_points = f.inliers.size();
    f.face.rms_m = std::sqrt(std::max(0.0, eig.eigenvalues()(0)) / double(f.inliers.size()));
}

// Bounding rectangle of the inliers in the plane (the long side is the width).
void fit_rectangle(const FeatureInput& in, FaceBuild& f) {
    PlanarFace& face = f.face;
    const Eigen::Vector3d u0 = face.normal.unitOrthogonal(), v0 = face.normal.cross(u0);
    std::vector<Eigen::Vector2d> uv;
    uv.reserve(f.inliers.size());
    for (std::size_t i : f.inliers) {
        const Eigen::Vector3d p = in.points[i].cast<double>();
        uv.emplace_back(p.dot(u0), p.dot(v0));
    }
    const Rectangle2 r = min_area_rectangle(uv);
    face.width_axis = (r.long_axis.x() * u0 + r.long_axis.y() * v0).normalized();
    face.height_axis = face.normal.cross(face.width_axis);
    face.centre_m = r.centre.x() * u0 + r.centre.y() * v0 + face.offset_m * face.normal;
    face.width_m = r.long_m;
    face.height_m = r.short_m;
    face.area_m2 = r.long_m * r.short_m;
}

// Medians over the thirds of a face along one of its axes: the inliers' normal component
// along the axis (first and last third) and their height above the plane (middle and
// outer thirds).
struct Thirds {
    double normal_turn = 0.0;  ///< Last third minus first (a sine): > 0 convex.
    double bulge_m = 0.0;      ///< Middle third minus the outer ones: > 0 convex.
    bool hollow = false;       ///< Under 5 % of the inliers in the middle third.
};

Thirds thirds_along(const FeatureInput& in, const FaceBuild& f, const Eigen::Vector3d& axis,
                    double half_extent_m) {
    std::vector<double> first, last, middle, outer;
    for (std::size_t i : f.inliers) {
        const Eigen::Vector3d p = in.points[i].cast<double>();
        const double t = (p - f.face.centre_m).dot(axis);
        const double n = in.normals[i].cast<double>().dot(axis);
        const double h = f.face.normal.dot(p) - f.face.offset_m;
        if (t < -half_extent_m / 3.0) first.push_back(n);
        if (t > half_extent_m / 3.0) last.push_back(n);
        (std::abs(t) < half_extent_m / 3.0 ? middle : outer).push_back(h);
    }
    if (first.size() < 10 || last.size() < 10) return {};
    if (20 * middle.size() < f.inliers.size()) return {.hollow = true};
    return {upper_median(std::move(last)) - upper_median(std::move(first)),
            upper_median(std::move(middle)) - upper_median(std::move(outer))};
}

// A strip of a curved surface (a column drum's mantle, a moulding's profile), or a plane
// cutting one (inliers in two bands, none in the middle), not a face. A strip: along one
// of its axes the normals turn steadily across it, and it bends as much as that turn
// says. A surface of constant curvature κ over a width w turns by 2κw/3 between the
// medians of its outer thirds and its middle third stands κw²·15/288 off the outer ones,
// so a turn τ comes with a bulge of τ·w·45/576 (the same sign: convex or concave). A
// 0.4 m drum's strips, 0.10-0.16 m wide, turn by 9-16 degrees and bulge 66-100 % of that;
// the rough back of a simulated wall block turned its inliers' normals by 6 degrees (the
// 4 mm band picks marks unevenly) with a bulge of -0.34 mm against 2.2 mm expected.
bool is_curved_strip(const FeatureInput& in, const FaceBuild& f, const FaceDetectionConfig& c) {
    const double min_turn = std::sin(c.strip_turn_deg * kDegToRad);
    for (const auto& [axis, half] : {std::pair{f.face.width_axis, 0.5 * f.face.width_m},
                                     std::pair{f.face.height_axis, 0.5 * f.face.height_m}}) {
        const Thirds t = thirds_along(in, f, axis, half);
        if (t.hollow) return true;
        const double expected_bulge_m = t.normal_turn * 2.0 * half * 45.0 / 576.0;
        if (std::abs(t.normal_turn) > min_turn &&
            t.bulge_m / expected_bulge_m >= c.strip_bend_agreement)
            return true;
    }
    return false;
}

// Assigns every input point to the plane it lies on best (distance and normal), so that
// all points count, not only the RANSAC subsample.
std::vector<FaceBuild> assign_points(const FeatureInput& in,
                                     const std::vector<DetectedPlane>& planes,
                                     const FaceDetectionConfig& c) {
    std::vector<FaceBuild> faces(planes.size());
    const double cos_max = std::cos(c.normal_threshold_deg * kDegToRad);
    for (std::size_t i = 0; i < in.points.size(); ++i) {
        const Eigen::Vector3d p = in.points[i].cast<double>(), n = in.normals[i].cast<double>();
        int best = -1;
        double best_d = c.epsilon_m;
        for (std::size_t f = 0; f < planes.size(); ++f) {
            const double d = std::abs(planes[f].normal.dot(p) - planes[f].offset_m);
            if (d < best_d && n.dot(planes[f].normal) > cos_max) best = int(f), best_d = d;
        }
        if (best >= 0) faces[best].inliers.push_back(i);
    }
    for (std::size_t f = 0; f < planes.size(); ++f) {
        faces[f].face.normal = planes[f].normal;
        faces[f].face.offset_m = planes[f].offset_m;
    }
    return faces;
}

// Merges each face into a larger one that is parallel and within merge_offset_m (a recess
// or a carved band of the same dressed face).
std::vector<FaceBuild> merge_parallel(std::vector<FaceBuild> faces, const FaceDetectionConfig& c) {
    std::sort(faces.begin(), faces.end(), [](const FaceBuild& a, const FaceBuild& b) {
        return a.inliers.size() > b.inliers.size();
    });
    const double cos_merge = std::cos(c.merge_angle_deg * kDegToRad);
    std::vector<FaceBuild> kept;
    for (FaceBuild& f : faces) {
        if (f.inliers.empty()) continue;
        auto host = std::find_if(kept.begin(), kept.end(), [&](const FaceBuild& k) {
            return k.face.normal.dot(f.face.normal) > cos_merge &&
                   std::abs(k.face.offset_m - f.face.offset_m) < c.merge_offset_m;
        });
        if (host == kept.end()) {
            kept.push_back(std::move(f));
        } else {
            host->inliers.insert(host->inliers.end(), f.inliers.begin(), f.inliers.end());
        }
    }
    return kept;
}

}  // namespace

std::vector<FaceBuild> find_faces(const FeatureInput& in, const FaceDetectionConfig& c) {
    const std::vector<std::size_t> sample = stride_sample(in.points.size(), c.max_ransac_points);
    std::vector<Eigen::Vector3f> sp, sn;
    for (std::size_t i : sample) sp.push_back(in.points[i]), sn.push_back(in.normals[i]);
    const double sample_spacing_m =
        in.spacing_m * std::sqrt(double(in.points.size()) / double(sample.size()));
    const double point_area_m2 = sample_spacing_m * sample_spacing_m;
    const RansacParams params{.epsilon_m = c.epsilon_m,
                              .cluster_epsilon_m = 4.0 * sample_spacing_m,
                              .normal_cos = std::cos(c.normal_threshold_deg * kDegToRad),
                              .min_points = std::max<std::size_t>(
                                  30, std::size_t(0.3 * c.min_face_area_m2 / point_area_m2)),
                              .probability = c.probability,
                              .seed = c.seed};
    std::vector<FaceBuild> faces = assign_points(in, detect_planes(sp, sn, params), c);
    for (FaceBuild& f : faces)
        if (f.inliers.size() >= 3) refit_plane(in, f, f.face.normal);
    faces = merge_parallel(std::move(faces), c);
    std::vector<FaceBuild> out;
    for (FaceBuild& f : faces) {
        if (f.inliers.size() < 3) continue;
        refit_plane(in, f, f.face.normal);
        fit_rectangle(in, f);
        if (f.face.area_m2 < c.min_face_area_m2 || is_curved_strip(in, f, c)) continue;
        // A face (not a strip of a curved surface, which the least-squares plane tells):
        // its plane is its dressed part's.
        set_plane(in, f, least_median_normal(in, f.inliers, f.face.normal));
        fit_rectangle(in, f);
        out.push_back(std::move(f));
    }
    for (std::size_t i = 0; i < out.size(); ++i) out[i].face.id = static_cast<int>(i);
    return out;
}

Eigen::Vector2d face_uv(const PlanarFace& face, const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - face.centre_m;
    return {d.dot(face.width_axis), d.dot(face.height_axis)};
}

}  // namespace anascan::reassembly::detail
