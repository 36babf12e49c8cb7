#pragma once
/// \file
/// PLY (Stanford polygon file format) read and write: ASCII, binary little and big endian.
///
/// Reading accepts any property order and any PLY scalar type for the vertex properties
/// x y z, nx ny nz, red green blue (also r g b / diffuse_*), intensity, confidence; the
/// first eight other scalar vertex properties are kept by name (`vertex_scalars`). `face` lists
/// become triangles (polygons are fan triangulated); the Stanford `range_grid` element is kept as a
/// RangeGrid; any other element is skipped and its name reported. An anascan origin comment
/// (`comment anascan origin_m X Y Z`) restores the double-precision origin.

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/range_grid.hpp"

namespace anascan::io {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

/// An extra per-vertex property written as `property float NAME` after the cloud's own
/// attributes (a mesh's support distance, its class); `values` is as long as the cloud.
struct PlyScalarProperty {
    std::string name;
    std::vector<float> values;
};

/// Everything a PLY file told us.
struct PlyData {
    PointCloud cloud;                        ///< The vertices and their attributes.
    std::vector<Eigen::Vector3i> triangles;  ///< Empty for point clouds.
    std::optional<RangeGrid> grid;           ///< Stanford range_grid, when present.
    PlyFormat format = PlyFormat::kBinaryLittleEndian;
    std::vector<std::string> comments;          ///< `comment` and `obj_info` lines, in order.
    std::vector<std::string> skipped_elements;  ///< Names of elements we did not read.
    /// The vertex's other scalar properties (the first eight, as floats), in file order.
    std::vector<PlyScalarProperty> vertex_scalars;
};

/// Parses PLY bytes. `source_name` (usually the path) starts every error message, followed
/// by the line (ASCII header/body) or byte offset (binary body) and what was wrong.
/// Never reads past `bytes`, never returns a partial cloud.
Expected<PlyData> parse_ply(std::span<const char> bytes, std::string_view source_name);

/// Reads and parses a PLY file.
Expected<PlyData> read_ply(const std::filesystem::path& path);

struct PlyWriteOptions {
    PlyFormat format = PlyFormat::kBinaryLittleEndian;
    std::vector<std::string> comments;              ///< Written as `comment` lines.
    std::vector<PlyScalarProperty> vertex_scalars;  ///< Extra vertex properties, in order.
};

/// Serialises a cloud (and optional triangles) to PLY bytes: float x y z, then float nx ny
/// nz, uchar red green blue, float intensity, float confidence for each attribute the
/// cloud has; a non-zero origin is written as a comment so that it round-trips exactly.
std::vector<char> serialize_ply(const PointCloud& cloud, std::span<const Eigen::Vector3i> triangles,
                                const PlyWriteOptions& options);

/// Writes a point cloud crash-safely (see write_file_atomically).
Expected<void> write_ply(const std::filesystem::path& path, const PointCloud& cloud,
                         const PlyWriteOptions& options = {});

/// Writes a mesh crash-safely.
Expected<void> write_ply(const std::filesystem::path& path, const Mesh& mesh,
                         const PlyWriteOptions& options = {});

}  // namespace anascan::io
