// Which part of a true surface a scanner could see from its true poses, against the
// classes of a model of it (see truth_comparison.hpp).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "anascan/processing/spatial/triangle_tree.hpp"
#include "anascan/processing/surface/mesh_distance.hpp"
#include "anascan/processing/surface/truth_comparison.hpp"

namespace anascan {
namespace {

double radians(double deg) { return deg * std::numbers::pi / 180.0; }

struct Sample {
    Eigen::Vector3d p, n;  ///< Truth frame, outward unit normal.
};

std::vector<Sample> truth_samples(const Mesh& truth, double spacing_m) {
    std::vector<Sample> out;
    const auto& v = truth.vertices.positions;
    for (const SurfaceSample& s : sample_surface(truth, spacing_m)) {
        const Eigen::Vector3i& t = truth.triangles[s.triangle];
        const Eigen::Vector3d a = v[t[0]].cast<double>(), b = v[t[1]].cast<double>(),
                              c = v[t[2]].cast<double>();
        out.push_back({s.position_m, (b - a).cross(c - a).normalized()});
    }
    return out;
}

class ViewCheck {
public:
    ViewCheck(const VisibilityConfig& c, const Mesh& truth)
        : config_(c),
          origin_(truth.vertices.origin_m),
          tan_h_(std::tan(radians(0.5 * c.horizontal_fov_deg))),
          tan_v_(std::tan(radians(0.5 * c.vertical_fov_deg))),
          cos_incidence_(std::cos(radians(c.max_incidence_deg))),
          tree_(truth.vertices.positions, truth.triangles) {}

    bool sees(const Pose& T_world_sensor, const Sample& s) const {
        const Eigen::Vector3d q = T_world_sensor.inverse() * s.p;  // sensor frame
        if (q.z() < config_.min_depth_m || q.z() > config_.max_depth_m) return false;
        if (std::abs(q.x()) > q.z() * tan_h_ || std::abs(q.y()) > q.z() * tan_v_) return false;
        const Eigen::Vector3d to_sensor = T_world_sensor.translation() - s.p;
        if (s.n.dot(to_sensor.normalized()) < cos_incidence_) return false;
        // Leave the surface by a little so that the sample's own triangle is not a hit.
        const Eigen::Vector3d from = s.p + 1e-4 * s.n - origin_;
        return !tree_.segment_hits(from, T_world_sensor.translation() - origin_);
    }

private:
    VisibilityConfig config_;
    Eigen::Vector3d origin_;
    double tan_h_, tan_v_, cos_incidence_;
    TriangleTree tree_;
};

}  // namespace

double VisibilityAgreement::seen_interpolated_share() const {
    return seen_area_m2 > 0.0 ? seen_interpolated_m2 / seen_area_m2 : 0.0;
}

double VisibilityAgreement::unseen_interpolated_share() const {
    return unseen_area_m2 > 0.0 ? unseen_interpolated_m2 / unseen_area_m2 : 1.0;
}

VisibilityAgreement compare_classes_with_visibility(const Mesh& model,
                                                    std::span<const SurfaceClass> triangle_class,
                                                    const Mesh& truth, std::span<const Pose> views,
                                                    const VisibilityConfig& config) {
    VisibilityAgreement out;
    if (model.triangles.empty() || truth.triangles.empty()) return out;
    const std::vector<Sample> samples = truth_samples(truth, config.sample_spacing_m);
    const ViewCheck check(config, truth);
    const MeshDistance to_model(model);
    std::vector<char> seen(samples.size(), 0), filled(samples.size(), 0),
        missing(samples.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 512), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            for (const Pose& T : views)
                if (check.sees(T, samples[i])) {
                    seen[i] = 1;
                    break;
                }
            double d = 0.0;
            std::size_t t = 0;
            const bool found = to_model.closest(samples[i].p, d, t);
            filled[i] =
                !found || d > config.match_within_m ||
                (!triangle_class.empty() && triangle_class[t] == SurfaceClass::kInterpolated);
        }
    });
    const double area = config.sample_spacing_m * config.sample_spacing_m;
    out.samples = samples.size();
    for (std::size_t i = 0; i < samples.size(); ++i) {
        (seen[i] ? out.seen_area_m2 : out.unseen_area_m2) += area;
        if (filled[i]) (seen[i] ? out.seen_interpolated_m2 : out.unseen_interpolated_m2) += area;
        if (missing[i]) (seen[i] ? out.seen_missing_m2 : out.unseen_missing_m2) += area;
    }
    return out;
}

}  // namespace anascan
