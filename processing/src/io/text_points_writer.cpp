// XYZ text output: one point per line, as parse_xyz reads it back.
#include <cstdio>
#include <string>

#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/text_points.hpp"

namespace anascan::io {
namespace {

/// `x y z` in world metres (origin added), then normals, or else intensity, then colours.
void append_point(const PointCloud& cloud, std::size_t i, std::string& out) {
    char line[192];
    const Eigen::Vector3d p = cloud.world_position(i);
    int n = std::snprintf(line, sizeof line, "%.6f %.6f %.6f", p.x(), p.y(), p.z());
    if (cloud.has_normals()) {
        const Eigen::Vector3f& v = cloud.normals[i];
        n += std::snprintf(line + n, sizeof line - n, " %.6f %.6f %.6f", v.x(), v.y(), v.z());
    } else if (cloud.has_intensity()) {
        n += std::snprintf(line + n, sizeof line - n, " %.6g", cloud.intensity[i]);
    }
    if (cloud.has_colors()) {
        const Rgb8& c = cloud.colors[i];
        n += std::snprintf(line + n, sizeof line - n, " %d %d %d", c.r, c.g, c.b);
    }
    out.append(line, static_cast<std::size_t>(n));
    out += '\n';
}

}  // namespace

std::string serialize_xyz(const PointCloud& cloud) {
    std::string out;
    out.reserve(cloud.size() * 40);
    for (std::size_t i = 0; i < cloud.size(); ++i) append_point(cloud, i, out);
    return out;
}

Expected<void> write_xyz(const std::filesystem::path& path, const PointCloud& cloud) {
    const std::string text = serialize_xyz(cloud);
    return write_file_atomically(path, std::span<const char>(text.data(), text.size()));
}

}  // namespace anascan::io
