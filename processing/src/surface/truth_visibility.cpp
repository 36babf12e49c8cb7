// Which part of a true surface a scanner could see from its true poses, against the
// classes of a model of it (see truth_comparison.hpp).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
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

// The field of view of one device, as tangents of its half-angles.
struct DeviceView {
    Pose T_view_device;
    double tan_h, tan_v;
};

constexpr double kNotSeen = 180.0;  // The incidence of a sample that no view sees.
constexpr double kBandDeg = 5.0;

class ViewCheck {
public:
    ViewCheck(const VisibilityConfig& c, const Mesh& truth)
        : config_(c),
          origin_(truth.vertices.origin_m),
          tree_(truth.vertices.positions, truth.triangles) {
        for (const VisibilityDevice& d : c.devices)
            devices_.push_back({d.T_view_device, std::tan(radians(0.5 * d.horizontal_fov_deg)),
                                std::tan(radians(0.5 * d.vertical_fov_deg))});
    }

    /// The smallest incidence (degrees) at which a view has the sample in sight of all its
    /// devices; kNotSeen when none has.
    double best_incidence_deg(std::span<const Pose> views, const Sample& s) const {
        double best = kNotSeen;
        for (const Pose& T_world_view : views) {
            const double deg = incidence_deg(T_world_view, s);
            if (deg < best && in_line_of_sight(T_world_view, s)) best = deg;
        }
        return best;
    }

private:
    // The largest incidence over the devices, kNotSeen if one has the sample out of its
    // field, its range, or behind the surface. Cheap: no ray test.
    double incidence_deg(const Pose& T_world_view, const Sample& s) const {
        if (devices_.empty()) return kNotSeen;
        double worst = 0.0;
        for (const DeviceView& d : devices_) {
            const Pose T_world_device = T_world_view * d.T_view_device;
            const Eigen::Vector3d q = T_world_device.inverse() * s.p;  // device frame
            if (q.z() < config_.min_depth_m || q.z() > config_.max_depth_m) return kNotSeen;
            if (std::abs(q.x()) > q.z() * d.tan_h || std::abs(q.y()) > q.z() * d.tan_v)
                return kNotSeen;
            const double c = s.n.dot((T_world_device.translation() - s.p).normalized());
            if (c <= 0.0) return kNotSeen;
            worst = std::max(worst, std::acos(std::min(c, 1.0)) * 180.0 / std::numbers::pi);
        }
        return worst;
    }

    bool in_line_of_sight(const Pose& T_world_view, const Sample& s) const {
        // Leave the surface by a little so that the sample's own triangle is not a hit.
        const Eigen::Vector3d from = s.p + 1e-4 * s.n - origin_;
        for (const DeviceView& d : devices_)
            if (tree_.segment_hits(from, (T_world_view * d.T_view_device).translation() - origin_))
                return false;
        return true;
    }

    VisibilityConfig config_;
    Eigen::Vector3d origin_;
    std::vector<DeviceView> devices_;
    TriangleTree tree_;
};

std::vector<IncidenceBand> empty_bands() {
    std::vector<IncidenceBand> bands;
    for (double from = 0.0; from < 90.0; from += kBandDeg)
        bands.push_back({.from_deg = from, .to_deg = from + kBandDeg});
    bands.push_back({.from_deg = 90.0, .to_deg = kNotSeen});
    return bands;
}

IncidenceBand& band_of(std::vector<IncidenceBand>& bands, double incidence_deg) {
    const auto k = static_cast<std::size_t>(std::min(incidence_deg, 90.0) / kBandDeg);
    return bands[std::min(k, bands.size() - 1)];
}

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
    out.bands = empty_bands();
    if (model.triangles.empty() || truth.triangles.empty()) return out;
    const std::vector<Sample> samples = truth_samples(truth, config.sample_spacing_m);
    const ViewCheck check(config, truth);
    const MeshDistance to_model(model);
    std::vector<double> incidence(samples.size(), kNotSeen);
    std::vector<char> filled(samples.size(), 0), missing(samples.size(), 0),
        covered(samples.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 512), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            incidence[i] = check.best_incidence_deg(views, samples[i]);
            double d = 0.0;
            std::size_t t = 0;
            const bool found = to_model.closest(samples[i].p, d, t);
            missing[i] = !found || d > config.match_within_m;
            covered[i] = found && d <= config.covered_within_m;
            filled[i] = missing[i] || (!triangle_class.empty() &&
                                       triangle_class[t] == SurfaceClass::kInterpolated);
        }
    });
    const double area = config.sample_spacing_m * config.sample_spacing_m;
    out.samples = samples.size();
    for (std::size_t i = 0; i < samples.size(); ++i) {
        IncidenceBand& band = band_of(out.bands, incidence[i]);
        band.area_m2 += area;
        if (filled[i]) band.interpolated_m2 += area;
        if (incidence[i] <= config.seen_incidence_deg) {
            out.seen_area_m2 += area;
            if (filled[i]) out.seen_interpolated_m2 += area;
            if (missing[i]) out.seen_missing_m2 += area;
            if (covered[i]) out.seen_covered_m2 += area;
        } else if (incidence[i] > config.unseen_incidence_deg) {
            out.unseen_area_m2 += area;
            if (filled[i]) out.unseen_interpolated_m2 += area;
            if (missing[i]) out.unseen_missing_m2 += area;
            if (covered[i]) out.unseen_covered_m2 += area;
        } else {
            out.grazing_area_m2 += area;
            if (filled[i]) out.grazing_interpolated_m2 += area;
            if (covered[i]) out.grazing_covered_m2 += area;
        }
    }
    return out;
}

}  // namespace anascan
