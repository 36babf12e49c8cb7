#pragma once
/// \file
/// Coverage of a stone's surface by a set of registered scans: the fraction of the surface
/// observed at sufficient sampling density and incidence angle, and the holes (connected
/// unobserved regions), largest first. See docs/coverage.md for the method and figures.
///
/// The surface is either estimated from the scans themselves (compute_coverage: ground
/// and background removed per scan, convex hull of the stone points) or given
/// (compute_coverage_on_surface: e.g. the ground-truth mesh of a simulated stone). The
/// same criterion decides whether a surface sample is observed: enough points of scans that
/// see it at a good incidence lie in a short cylinder under it.
///
/// Library code: no I/O, parallel loops with TBB, results independent of the thread count.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/cleaning/plane_removal.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"

namespace anascan {

/// One registered scan as coverage sees it. The cloud must outlive the call.
struct CoverageScanView {
    const PointCloud* cloud = nullptr;     ///< Points in the scan frame.
    Pose T_world_scan = Pose::Identity();  ///< Registered pose (world = the model's frame).
    /// Sensor position in the scan frame, metres; absent: incidence is not checked.
    std::optional<Eigen::Vector3d> sensor_origin_scan_m;
    /// Captured points each point stands for (> 0): 1 for a raw scan, the mean points per
    /// voxel for a down-sampled copy, so that density is measured in captured points.
    double points_per_point = 1.0;
};

struct CoverageConfig {
    /// The criterion.
    double sample_spacing_m = 0.005;    ///< Mean distance between surface samples.
    double min_density_per_cm2 = 10.0;  ///< Captured points per cm² (10: ~3 mm spacing).
    double max_incidence_deg = 70.0;    ///< Normal vs direction to the sensor.
    double cylinder_radius_m = 0.004;   ///< Radius of the cylinder under a sample.
    double depth_below_m = 0.015;       ///< Cylinder depth into the stone (concavities).
    double depth_above_m = 0.004;       ///< Cylinder height above the surface (noise).
    double bin_size_m = 0.003;          ///< Scans are binned (counts kept) before counting.
    /// Each scan is first thinned to this many points, evenly in its order (each kept point
    /// stands for the skipped ones), so the time does not grow with the scanner's resolution.
    std::size_t max_points_per_view = 40000;
    /// The surface estimate (compute_coverage only).
    double ground_distance_m = 0.003;     ///< Points this close to the ground are ground.
    double cluster_voxel_m = 0.01;        ///< Voxels linking the stone's points.
    double min_cluster_voxel_points = 3;  ///< Captured points for a voxel to count.
    /// Holes smaller than this are not listed (their samples still count as unobserved).
    double min_hole_area_m2 = 1e-4;
    std::uint64_t seed = 1;  ///< Surface sampling: fixed, reproducible.
};

enum class CoverageStatus {
    kOk,
    kNoScans,         ///< No view with points.
    kNoStone,         ///< Too few stone points to estimate a surface (compute_coverage).
    kInvalidSurface,  ///< The surface has no area (or the hull failed).
};

/// What a surface sample saw.
enum class SampleState : std::uint8_t {
    kObserved,    ///< Dense enough at a good incidence (green).
    kSparse,      ///< Some points, but too few or too grazing (yellow).
    kUnobserved,  ///< Nothing (red).
};

/// A connected unobserved region (sparse or unobserved samples).
struct CoverageHole {
    double area_m2 = 0.0;
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< World frame.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();    ///< Mean outward normal, unit.
    std::size_t sample_count = 0;
};

struct CoverageReport {
    CoverageStatus status = CoverageStatus::kNoScans;
    double fraction = 0.0;            ///< Observed area / surface area, 0..1.
    double surface_area_m2 = 0.0;     ///< Of the estimated (or given) surface.
    double covered_area_m2 = 0.0;     ///< Observed.
    double sparse_area_m2 = 0.0;      ///< Seen, but too sparse or too grazing.
    std::vector<CoverageHole> holes;  ///< Largest first, at least min_hole_area_m2 each.
    /// The surface samples, world frame, with outward normals and colours (green observed,
    /// yellow sparse, red unobserved), for a PLY.
    PointCloud samples;
    std::vector<SampleState> sample_states;  ///< One per sample.
    Mesh surface;                            ///< The surface used, world frame.
    std::size_t stone_point_count = 0;       ///< Binned points kept as stone (estimate).
    /// The ground the stone rests on now: that of the last view (in input order) with a
    /// ground, world frame, normal up (toward the stone). Absent when no view showed one, and
    /// for compute_coverage_on_surface.
    std::optional<Plane> ground_world;
    std::string message;  ///< Why, when not kOk.
};

/// Estimates the stone's surface from the scans and measures its coverage. Per scan, the
/// ground plane and what lies beyond it are removed; of the rest, the connected cluster
/// nearest the model's median point is the stone. As the stone rests on the ground, its
/// points are also projected onto their scan's ground; the convex hull of both is the
/// surface (the face it rests on, and sides never seen down to the ground, become holes).
CoverageReport compute_coverage(std::span<const CoverageScanView> scans,
                                const CoverageConfig& config);

/// The same criterion on a given closed surface (world frame, outward triangles), with
/// every point of the scans (nothing removed): the ground truth of compute_coverage.
CoverageReport compute_coverage_on_surface(const Mesh& surface_world,
                                           std::span<const CoverageScanView> scans,
                                           const CoverageConfig& config);

/// Short name of a status ("ok", "no-scans", ...), for logs and JSON.
const char* to_string(CoverageStatus status);

/// The colour of a sample's state in the samples' PLY and in the field app's legend:
/// green observed, yellow sparse, red unobserved.
Rgb8 coverage_sample_color(SampleState state);

/// The report as a JSON object (status, fraction, areas in m², holes with area_m2,
/// centre_m, normal; at most `max_holes` holes), for the session store and `--json`.
std::string coverage_to_json(const CoverageReport& report, std::size_t max_holes = 20);

/// The report as coverage_to_json wrote it, read back: each figure absent when the text
/// lacks it; holes as listed (at most the writer's max_holes, largest first).
struct CoverageSummary {
    std::optional<CoverageStatus> status;
    std::optional<double> fraction;  ///< Observed area / surface area, 0..1.
    std::optional<double> surface_area_m2, covered_area_m2, sparse_area_m2;
    std::optional<std::size_t> hole_count;  ///< All holes found (the list may be shorter).
    std::vector<CoverageHole> holes;        ///< The listed holes that parse.
    std::size_t malformed_holes = 0;        ///< Listed, but missing a field: skipped.
    std::string message;                    ///< Why, when not ok.
};

/// Reads coverage_to_json's text; kFormat when it is not a JSON object.
Expected<CoverageSummary> coverage_from_json(std::string_view json);

}  // namespace anascan
