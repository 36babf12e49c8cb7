#include <bit>
#include <cassert>
#include <charconv>
#include <cstdio>
#include <cstring>

#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"
#include "ply_header.hpp"
#include "ply_source.hpp"

namespace anascan::io {
namespace {

using ply_detail::byte_swapped;

// Which attributes are written: those exactly as long as positions.
struct VertexLayout {
    /// Positions as absolute double coordinates (origin + local): other programs (MeshLab,
    /// CloudCompare, Open3D) ignore our origin comment, so the values must stand alone.
    bool absolute = false;
    bool normals = false, colors = false, intensity = false, confidence = false;
    std::span<const PlyScalarProperty> scalars;  ///< Extra float properties, last.

    VertexLayout(const PointCloud& cloud, std::span<const PlyScalarProperty> extra)
        : absolute(cloud.origin_m != Eigen::Vector3d::Zero()),
          normals(cloud.normals.size() == cloud.size() && cloud.has_normals()),
          colors(cloud.colors.size() == cloud.size() && cloud.has_colors()),
          intensity(cloud.intensity.size() == cloud.size() && cloud.has_intensity()),
          confidence(cloud.confidence.size() == cloud.size() && cloud.has_confidence()),
          scalars(extra) {}

    std::size_t record_bytes() const {
        return (absolute ? 24 : 12) + (normals ? 12 : 0) + (colors ? 3 : 0) + (intensity ? 4 : 0) +
               (confidence ? 4 : 0) + 4 * scalars.size();
    }
};

std::string_view format_name(PlyFormat format) {
    switch (format) {
        case PlyFormat::kAscii:
            return "ascii";
        case PlyFormat::kBinaryLittleEndian:
            return "binary_little_endian";
        case PlyFormat::kBinaryBigEndian:
            return "binary_big_endian";
    }
    return "ascii";
}

// A comment must stay on one header line: line breaks become spaces.
std::string one_line(std::string_view text) {
    std::string line(text);
    for (char& c : line) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    return line;
}

std::string header_text(const PointCloud& cloud, std::size_t triangle_count,
                        const PlyWriteOptions& options, const VertexLayout& layout) {
    std::string text = "ply\nformat " + std::string(format_name(options.format)) + " 1.0\n";
    for (const std::string& comment : options.comments) {
        if (comment.starts_with(ply_detail::kOriginComment)) continue;  // written below
        text += "comment " + one_line(comment) + "\n";
    }
    if (cloud.origin_m != Eigen::Vector3d::Zero()) {
        char origin[128];
        std::snprintf(origin, sizeof(origin), "comment %s %.17g %.17g %.17g\n",
                      ply_detail::kOriginComment.data(), cloud.origin_m.x(), cloud.origin_m.y(),
                      cloud.origin_m.z());
        text += origin;
    }
    text += "element vertex " + std::to_string(cloud.size()) + "\n";
    text += layout.absolute ? "property double x\nproperty double y\nproperty double z\n"
                            : "property float x\nproperty float y\nproperty float z\n";
    if (layout.normals) text += "property float nx\nproperty float ny\nproperty float nz\n";
    if (layout.colors) text += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    if (layout.intensity) text += "property float intensity\n";
    if (layout.confidence) text += "property float confidence\n";
    for (const PlyScalarProperty& s : layout.scalars) text += "property float " + s.name + "\n";
    if (triangle_count > 0) {
        text += "element face " + std::to_string(triangle_count) + "\n";
        text += "property list uchar int vertex_indices\n";
    }
    return text + "end_header\n";
}

template <bool kSwap, class T>
char* put(char* out, T value) {
    if constexpr (kSwap) value = byte_swapped(value);
    std::memcpy(out, &value, sizeof(T));
    return out + sizeof(T);
}

template <bool kSwap>
char* put3(char* out, const Eigen::Vector3f& v) {
    if constexpr (!kSwap) {
        std::memcpy(out, v.data(), 12);
        return out + 12;
    }
    out = put<kSwap>(out, v.x());
    out = put<kSwap>(out, v.y());
    return put<kSwap>(out, v.z());
}

template <bool kSwap>
char* put_position(char* out, const PointCloud& cloud, std::size_t i, const VertexLayout& layout) {
    if (!layout.absolute) return put3<kSwap>(out, cloud.positions[i]);
    const Eigen::Vector3d p = cloud.world_position(i);
    out = put<kSwap>(out, p.x());
    out = put<kSwap>(out, p.y());
    return put<kSwap>(out, p.z());
}

template <bool kSwap>
void write_binary_body(const PointCloud& cloud, std::span<const Eigen::Vector3i> triangles,
                       const VertexLayout& layout, char* out) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        out = put_position<kSwap>(out, cloud, i, layout);
        if (layout.normals) out = put3<kSwap>(out, cloud.normals[i]);
        if (layout.colors) {
            const Rgb8 c = cloud.colors[i];
            *out++ = static_cast<char>(c.r);
            *out++ = static_cast<char>(c.g);
            *out++ = static_cast<char>(c.b);
        }
        if (layout.intensity) out = put<kSwap>(out, cloud.intensity[i]);
        if (layout.confidence) out = put<kSwap>(out, cloud.confidence[i]);
        for (const PlyScalarProperty& s : layout.scalars) out = put<kSwap>(out, s.values[i]);
    }
    for (const Eigen::Vector3i& t : triangles) {
        *out++ = 3;
        for (int k = 0; k < 3; ++k) out = put<kSwap>(out, static_cast<std::int32_t>(t[k]));
    }
}

// Appends shortest round-trip text for each value, separated by spaces, to `out`.
class AsciiLine {
public:
    explicit AsciiLine(std::vector<char>& out) : out_(out) {}

    template <class T>
    void add(T value) {
        char text[32];  // a float, double or int needs at most 24 characters
        const auto [end, ec] = std::to_chars(text, text + sizeof(text), value);
        assert(ec == std::errc());
        if (!first_) out_.push_back(' ');
        out_.insert(out_.end(), text, end);
        first_ = false;
    }
    void add3(const Eigen::Vector3f& v) {
        add(v.x());
        add(v.y());
        add(v.z());
    }
    void end() {
        out_.push_back('\n');
        first_ = true;
    }

private:
    std::vector<char>& out_;
    bool first_ = true;
};

void write_ascii_body(const PointCloud& cloud, std::span<const Eigen::Vector3i> triangles,
                      const VertexLayout& layout, std::vector<char>& out) {
    out.reserve(out.size() + cloud.size() * (layout.record_bytes() * 3) + triangles.size() * 40);
    AsciiLine line(out);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (layout.absolute) {
            const Eigen::Vector3d p = cloud.world_position(i);
            line.add(p.x());
            line.add(p.y());
            line.add(p.z());
        } else {
            line.add3(cloud.positions[i]);
        }
        if (layout.normals) line.add3(cloud.normals[i]);
        if (layout.colors) {
            line.add(static_cast<int>(cloud.colors[i].r));
            line.add(static_cast<int>(cloud.colors[i].g));
            line.add(static_cast<int>(cloud.colors[i].b));
        }
        if (layout.intensity) line.add(cloud.intensity[i]);
        if (layout.confidence) line.add(cloud.confidence[i]);
        for (const PlyScalarProperty& s : layout.scalars) line.add(s.values[i]);
        line.end();
    }
    for (const Eigen::Vector3i& t : triangles) {
        line.add(3);
        for (int k = 0; k < 3; ++k) line.add(t[k]);
        line.end();
    }
}

Expected<void> check_mesh(const std::filesystem::path& path, const PointCloud& cloud,
                          std::span<const Eigen::Vector3i> triangles,
                          std::span<const PlyScalarProperty> scalars) {
    if (!cloud.attributes_consistent()) {
        return fail(ErrorCode::kInvalidArgument,
                    path.string() + ": cannot write PLY: " + describe_inconsistency(cloud));
    }
    for (const PlyScalarProperty& s : scalars) {
        if (s.values.size() != cloud.size() || s.name.empty() ||
            s.name.find_first_of(" \t\r\n") != std::string::npos) {
            return fail(ErrorCode::kInvalidArgument,
                        path.string() + ": cannot write PLY: vertex property '" + s.name +
                            "' has " + std::to_string(s.values.size()) + " values for " +
                            std::to_string(cloud.size()) + " vertices (or a bad name)");
        }
    }
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            if (triangles[i][k] < 0 || static_cast<std::size_t>(triangles[i][k]) >= cloud.size()) {
                return fail(ErrorCode::kInvalidArgument,
                            path.string() + ": cannot write PLY: triangle " + std::to_string(i) +
                                " refers to vertex " + std::to_string(triangles[i][k]) + " of " +
                                std::to_string(cloud.size()));
            }
        }
    }
    return {};
}

}  // namespace

std::vector<char> serialize_ply(const PointCloud& cloud, std::span<const Eigen::Vector3i> triangles,
                                const PlyWriteOptions& options) {
    assert(cloud.attributes_consistent());
    const VertexLayout layout(cloud, options.vertex_scalars);
    const std::string header = header_text(cloud, triangles.size(), options, layout);
    std::vector<char> out(header.begin(), header.end());
    if (options.format == PlyFormat::kAscii) {
        write_ascii_body(cloud, triangles, layout, out);
        return out;
    }
    const std::size_t body = cloud.size() * layout.record_bytes() + triangles.size() * 13;
    out.resize(header.size() + body);
    const bool file_little = options.format == PlyFormat::kBinaryLittleEndian;
    const bool swap = file_little != (std::endian::native == std::endian::little);
    char* start = out.data() + header.size();
    if (swap) {
        write_binary_body<true>(cloud, triangles, layout, start);
    } else {
        write_binary_body<false>(cloud, triangles, layout, start);
    }
    return out;
}

Expected<void> write_ply(const std::filesystem::path& path, const PointCloud& cloud,
                         const PlyWriteOptions& options) {
    if (Expected<void> ok = check_mesh(path, cloud, {}, options.vertex_scalars); !ok) return ok;
    return write_file_atomically(path, serialize_ply(cloud, {}, options));
}

Expected<void> write_ply(const std::filesystem::path& path, const Mesh& mesh,
                         const PlyWriteOptions& options) {
    if (Expected<void> ok = check_mesh(path, mesh.vertices, mesh.triangles, options.vertex_scalars);
        !ok)
        return ok;
    return write_file_atomically(path, serialize_ply(mesh.vertices, mesh.triangles, options));
}

}  // namespace anascan::io
