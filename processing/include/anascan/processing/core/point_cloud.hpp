#pragma once
/// \file
/// The point cloud: a struct of arrays in a local float frame with a double-precision origin.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace anascan {

/// 8-bit RGB colour, as scanners and PLY files store it.
struct Rgb8 {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

/// Points of one scan or model, stored as a struct of arrays.
///
/// Coordinates are float, in metres, relative to `origin_m` (double, same frame), so that
/// site coordinates of a terrestrial scanner (hundreds of kilometres) keep sub-millimetre
/// precision: the world position of point i is `origin_m + positions[i].cast<double>()`.
/// Every optional attribute is either empty or exactly as long as `positions`; use
/// `attributes_consistent()` to check. Not thread-safe for concurrent modification;
/// concurrent reads are fine.
struct PointCloud {
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();  ///< Local frame origin, metres.
    std::vector<Eigen::Vector3f> positions;              ///< Metres, relative to origin_m.
    std::vector<Eigen::Vector3f> normals;                ///< Unit vectors, optional.
    std::vector<Rgb8> colors;                            ///< Optional.
    std::vector<float> intensity;                        ///< Scanner units, optional.
    std::vector<float> confidence;                       ///< 0..1 per point, optional.

    std::size_t size() const { return positions.size(); }
    bool empty() const { return positions.empty(); }
    bool has_normals() const { return !normals.empty(); }
    bool has_colors() const { return !colors.empty(); }
    bool has_intensity() const { return !intensity.empty(); }
    bool has_confidence() const { return !confidence.empty(); }

    /// True when every optional attribute is empty or as long as `positions`.
    bool attributes_consistent() const;

    /// World (origin-relative-to-nothing) position of point i, metres, in double.
    Eigen::Vector3d world_position(std::size_t i) const {
        return origin_m + positions[i].cast<double>();
    }

    /// Reserves room for n points in positions and in every attribute already present.
    void reserve(std::size_t n);
};

/// Human-readable description of what is inconsistent, or empty when consistent.
std::string describe_inconsistency(const PointCloud& cloud);

/// The points at `indices` (in that order), with every attribute the cloud has.
PointCloud select(const PointCloud& cloud, std::span<const std::size_t> indices);

/// Appends `other` to `cloud`, re-expressing its points relative to `cloud.origin_m`.
/// An attribute survives only when both clouds have it (or `cloud` is empty).
void append(PointCloud& cloud, const PointCloud& other);

/// Removes points with a non-finite coordinate (NaN/inf from a scanner's invalid returns).
/// Returns how many points were removed.
std::size_t remove_non_finite(PointCloud& cloud);

/// Axis-aligned bounds of the local positions (metres, local frame).
struct Bounds {
    Eigen::Vector3f min = Eigen::Vector3f::Zero();
    Eigen::Vector3f max = Eigen::Vector3f::Zero();
    Eigen::Vector3f extent() const { return max - min; }
};

/// Bounds of the cloud's local positions; zero bounds for an empty cloud.
Bounds local_bounds(const PointCloud& cloud);

}  // namespace anascan
