// Wavefront OBJ read and write.
#include <charconv>
#include <cmath>
#include <cstdio>

#include "anascan/processing/io/mesh_formats.hpp"
#include "text_lines.hpp"

namespace anascan::io {
namespace {

using text::LineRef;

struct ObjState {
    std::vector<Eigen::Vector3d> v;
    std::vector<Eigen::Vector3f> vn;
    std::vector<int> normal_of_vertex;  // -1 none, -2 conflicting
    std::vector<Eigen::Vector3i> triangles;
};

// Resolves a 1-based or negative index against `count` items; 0-based result.
Expected<int> resolve_index(std::string_view token, std::size_t count, const char* what,
                            LineRef where) {
    long long value = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size() || value == 0) {
        return text::line_error(ErrorCode::kFormat, where,
                                "bad " + std::string(what) + " index '" + std::string(token) + "'");
    }
    const long long n = static_cast<long long>(count);
    const long long index = value > 0 ? value - 1 : n + value;
    if (index < 0 || index >= n) {
        return text::line_error(ErrorCode::kFormat, where,
                                std::string(what) + " index " + std::string(token) +
                                    " out of range (" + std::to_string(count) + " defined so far)");
    }
    return static_cast<int>(index);
}

Expected<Eigen::Vector3d> parse_xyz(const text::Fields& f, LineRef where) {
    if (f.count < 4) return text::line_error(ErrorCode::kFormat, where, "expected 3 coordinates");
    double xyz[3];
    if (auto ok = text::parse_doubles(f, 1, xyz, where); !ok) return fail(ok.error());
    // Positions are stored as floats about an origin: a coordinate beyond this cannot be
    // stored (and is no stone).
    constexpr double kMaxCoordinate = 1e9;
    for (const double c : xyz) {
        if (!(std::abs(c) <= kMaxCoordinate)) {
            return text::line_error(ErrorCode::kFormat, where,
                                    "coordinate out of range (|value| > 1e9)");
        }
    }
    return Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
}

Expected<void> parse_corner(std::string_view corner, ObjState& s, int& vertex, LineRef where) {
    const std::size_t slash = corner.find('/');
    auto v = resolve_index(corner.substr(0, slash), s.v.size(), "vertex", where);
    if (!v) return fail(v.error());
    vertex = *v;
    const std::size_t second =
        slash == std::string_view::npos ? slash : corner.find('/', slash + 1);
    if (second == std::string_view::npos || second + 1 >= corner.size()) return {};
    auto n = resolve_index(corner.substr(second + 1), s.vn.size(), "normal", where);
    if (!n) return fail(n.error());
    int& slot = s.normal_of_vertex[vertex];
    slot = (slot == -1 || slot == *n) ? *n : -2;
    return {};
}

Expected<void> parse_face(const text::Fields& f, ObjState& s, LineRef where) {
    if (f.count < 4) return text::line_error(ErrorCode::kFormat, where, "a face needs 3 corners");
    if (f.count > text::Fields::kMax) {
        return text::line_error(ErrorCode::kUnsupported, where,
                                "face with " + std::to_string(f.count - 1) + " corners (at most " +
                                    std::to_string(text::Fields::kMax - 1) + ")");
    }
    int corners[text::Fields::kMax];
    for (std::size_t i = 1; i < f.count; ++i) {
        if (auto ok = parse_corner(f[i], s, corners[i - 1], where); !ok) return ok;
    }
    for (std::size_t i = 2; i + 1 < f.count; ++i) {
        s.triangles.emplace_back(corners[0], corners[i - 1], corners[i]);
    }
    return {};
}

Expected<void> parse_statement(const text::Fields& f, ObjState& s, LineRef where) {
    if (f[0] == "v") {
        auto p = parse_xyz(f, where);
        if (!p) return fail(p.error());
        s.v.push_back(*p);
        s.normal_of_vertex.push_back(-1);
    } else if (f[0] == "vn") {
        auto n = parse_xyz(f, where);
        if (!n) return fail(n.error());
        s.vn.push_back(n->normalized().cast<float>());
    } else if (f[0] == "f") {
        return parse_face(f, s, where);
    }
    return {};
}

Mesh to_mesh(ObjState& s) {
    Mesh mesh;
    if (!s.v.empty()) mesh.vertices.origin_m = text::origin_for(s.v.front());
    for (const Eigen::Vector3d& p : s.v) {
        mesh.vertices.positions.push_back((p - mesh.vertices.origin_m).cast<float>());
    }
    bool all_normals = !s.v.empty();
    for (const int n : s.normal_of_vertex) all_normals = all_normals && n >= 0;
    if (all_normals) {
        for (const int n : s.normal_of_vertex) mesh.vertices.normals.push_back(s.vn[n]);
    }
    mesh.triangles = std::move(s.triangles);
    return mesh;
}

}  // namespace

Expected<Mesh> parse_obj(std::span<const char> bytes, std::string_view source_name) {
    text::LineReader reader(bytes, false);  // `//` is a corner separator in OBJ, not a comment
    ObjState s;
    while (reader.next()) {
        const std::string_view line = reader.line().substr(0, reader.line().find('#'));
        const text::Fields f = text::split_fields(line, text::kBlanks);
        if (f.count == 0) continue;
        const LineRef where{source_name, reader.line_number()};
        if (auto ok = parse_statement(f, s, where); !ok) return fail(ok.error());
    }
    if (s.v.empty()) {
        return text::line_error(ErrorCode::kEmpty, {source_name, reader.line_number()},
                                "no vertices");
    }
    return to_mesh(s);
}

std::vector<char> serialize_obj(const Mesh& mesh) {
    std::vector<char> out;
    const PointCloud& v = mesh.vertices;
    const bool normals = v.normals.size() == v.size() && !v.empty();
    char line[160];
    const auto put = [&](int n) { out.insert(out.end(), line, line + n); };
    put(std::snprintf(line, sizeof(line), "# anascan mesh: %zu vertices, %zu triangles\n", v.size(),
                      mesh.triangles.size()));
    for (std::size_t i = 0; i < v.size(); ++i) {
        const Eigen::Vector3d p = v.world_position(i);
        put(std::snprintf(line, sizeof(line), "v %.9g %.9g %.9g\n", p.x(), p.y(), p.z()));
    }
    for (std::size_t i = 0; normals && i < v.size(); ++i) {
        const Eigen::Vector3f& n = v.normals[i];
        put(std::snprintf(line, sizeof(line), "vn %.6g %.6g %.6g\n", n.x(), n.y(), n.z()));
    }
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const int a = t[0] + 1, b = t[1] + 1, c = t[2] + 1;
        put(normals
                ? std::snprintf(line, sizeof(line), "f %d//%d %d//%d %d//%d\n", a, a, b, b, c, c)
                : std::snprintf(line, sizeof(line), "f %d %d %d\n", a, b, c));
    }
    return out;
}

}  // namespace anascan::io
