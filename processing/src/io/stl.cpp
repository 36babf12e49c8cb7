// STL read (binary and ASCII) and binary write.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <map>

#include "anascan/processing/io/mesh_formats.hpp"
#include "ply_source.hpp"
#include "text_lines.hpp"

namespace anascan::io {
namespace {

constexpr std::size_t kHeaderBytes = 84, kTriangleBytes = 50;

// Welds corners with bit-identical coordinates into shared vertices.
class Welder {
public:
    int add(const Eigen::Vector3f& p) {
        const auto [it, inserted] = index_.try_emplace(key(p), static_cast<int>(points_.size()));
        if (inserted) points_.push_back(p);
        return it->second;
    }
    std::vector<Eigen::Vector3f> take() { return std::move(points_); }

private:
    static std::array<std::uint32_t, 3> key(const Eigen::Vector3f& p) {
        return {std::bit_cast<std::uint32_t>(p.x() + 0.0f),
                std::bit_cast<std::uint32_t>(p.y() + 0.0f),
                std::bit_cast<std::uint32_t>(p.z() + 0.0f)};
    }
    std::map<std::array<std::uint32_t, 3>, int> index_;
    std::vector<Eigen::Vector3f> points_;
};

Unexpected<Error> byte_error(ErrorCode code, std::string_view source, std::size_t offset,
                             const std::string& what) {
    return fail(code, std::string(source) + ": byte " + std::to_string(offset) + ": " + what);
}

float read_float(const char* p) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, p, 4);
    if constexpr (std::endian::native == std::endian::big) bits = ply_detail::byte_swapped(bits);
    return std::bit_cast<float>(bits);
}

Expected<Mesh> parse_binary(std::span<const char> bytes, std::uint32_t count,
                            std::string_view source) {
    Welder welder;
    Mesh mesh;
    mesh.triangles.reserve(count);
    for (std::uint32_t t = 0; t < count; ++t) {
        const std::size_t at = kHeaderBytes + std::size_t(t) * kTriangleBytes;
        Eigen::Vector3i tri;
        for (int k = 0; k < 3; ++k) {
            const char* p = bytes.data() + at + 12 + 12 * k;
            const Eigen::Vector3f v(read_float(p), read_float(p + 4), read_float(p + 8));
            if (!v.allFinite()) {
                return byte_error(ErrorCode::kFormat, source, at + 12 + 12 * k,
                                  "triangle " + std::to_string(t) + " of " + std::to_string(count) +
                                      ": non-finite vertex");
            }
            tri[k] = welder.add(v);
        }
        mesh.triangles.push_back(tri);
    }
    mesh.vertices.positions = welder.take();
    return mesh;
}

Expected<void> expect_keyword(const text::Fields& f, std::string_view word, text::LineRef where) {
    if (f.count >= 1 && f[0] == word) return {};
    return text::line_error(
        ErrorCode::kFormat, where,
        "expected '" + std::string(word) + "', found '" + std::string(f.count ? f[0] : "") + "'");
}

// One `facet` ... `endfacet` block; the reader is on the `facet` line.
Expected<void> parse_facet(text::LineReader& r, std::string_view source, Welder& welder,
                           Mesh& mesh) {
    const auto next_fields = [&](std::string_view word) -> Expected<text::Fields> {
        if (!r.next()) {
            return text::line_error(
                ErrorCode::kTruncated, {source, r.line_number()},
                "file ends inside a facet (expected '" + std::string(word) + "')");
        }
        const text::Fields f = text::split_fields(r.line(), text::kBlanks);
        if (auto ok = expect_keyword(f, word, {source, r.line_number()}); !ok)
            return fail(ok.error());
        return f;
    };
    if (auto f = next_fields("outer"); !f) return fail(f.error());
    Eigen::Vector3i tri;
    for (int k = 0; k < 3; ++k) {
        auto f = next_fields("vertex");
        if (!f) return fail(f.error());
        const text::LineRef where{source, r.line_number()};
        if (f->count != 4)
            return text::line_error(ErrorCode::kFormat, where, "expected 3 coordinates");
        double xyz[3];
        if (auto ok = text::parse_doubles(*f, 1, xyz, where); !ok) return fail(ok.error());
        Eigen::Vector3f v;
        for (int a = 0; a < 3; ++a) {
            auto c = text::to_float(xyz[a], std::size_t(a) + 2, where);
            if (!c) return fail(c.error());
            v[a] = *c;
        }
        tri[k] = welder.add(v);
    }
    if (auto f = next_fields("endloop"); !f) return fail(f.error());
    if (auto f = next_fields("endfacet"); !f) return fail(f.error());
    mesh.triangles.push_back(tri);
    return {};
}

Expected<Mesh> parse_ascii(std::span<const char> bytes, std::string_view source) {
    text::LineReader r(bytes, false);
    Welder welder;
    Mesh mesh;
    bool ended = false;
    if (!r.next()) return text::line_error(ErrorCode::kEmpty, {source, 1}, "empty file");
    while (r.next()) {
        const text::Fields f = text::split_fields(r.line(), text::kBlanks);
        const text::LineRef where{source, r.line_number()};
        if (f[0] == "endsolid") {
            ended = true;
            break;
        }
        if (auto ok = expect_keyword(f, "facet", where); !ok) return fail(ok.error());
        if (auto ok = parse_facet(r, source, welder, mesh); !ok) return fail(ok.error());
    }
    if (!ended) {
        return text::line_error(ErrorCode::kTruncated, {source, r.line_number()},
                                "no 'endsolid' line");
    }
    mesh.vertices.positions = welder.take();
    if (mesh.triangles.empty()) {
        return text::line_error(ErrorCode::kEmpty, {source, r.line_number()}, "no facets");
    }
    return mesh;
}

bool starts_with_solid(std::span<const char> bytes) {
    std::string_view head(bytes.data(), std::min<std::size_t>(bytes.size(), 80));
    const std::size_t first = head.find_first_not_of(" \t\r\n");
    return first != std::string_view::npos && head.substr(first).starts_with("solid");
}

}  // namespace

Expected<Mesh> parse_stl(std::span<const char> bytes, std::string_view source_name) {
    if (bytes.size() >= kHeaderBytes) {
        std::uint32_t count = 0;
        std::memcpy(&count, bytes.data() + 80, 4);
        if constexpr (std::endian::native == std::endian::big)
            count = ply_detail::byte_swapped(count);
        const std::size_t needed = kHeaderBytes + std::size_t(count) * kTriangleBytes;
        if (needed == bytes.size()) {
            if (count == 0) return byte_error(ErrorCode::kEmpty, source_name, 80, "no triangles");
            return parse_binary(bytes, count, source_name);
        }
        if (!starts_with_solid(bytes)) {
            return byte_error(bytes.size() < needed ? ErrorCode::kTruncated : ErrorCode::kFormat,
                              source_name, 80,
                              "binary STL announces " + std::to_string(count) + " triangles (" +
                                  std::to_string(needed) + " bytes) but the file has " +
                                  std::to_string(bytes.size()) + " bytes");
        }
    }
    if (starts_with_solid(bytes)) return parse_ascii(bytes, source_name);
    return byte_error(ErrorCode::kFormat, source_name, 0,
                      "neither binary STL (shorter than its 84-byte header) nor ASCII STL (no "
                      "'solid' line)");
}

std::vector<char> serialize_stl(const Mesh& mesh) {
    std::string header = "anascan binary STL, metres";
    header.resize(80, ' ');
    const std::uint32_t count = static_cast<std::uint32_t>(mesh.triangles.size());
    for (int b = 0; b < 4; ++b) header.push_back(static_cast<char>((count >> (8 * b)) & 0xffu));
    std::vector<char> out(header.begin(), header.end());
    out.resize(header.size() + mesh.triangles.size() * kTriangleBytes);
    char* p = out.data() + header.size();
    const auto put = [&p](const Eigen::Vector3f& v) {
        std::memcpy(p, v.data(), 12);
        p += 12;
    };
    for (const Eigen::Vector3i& t : mesh.triangles) {
        Eigen::Vector3f c[3];
        for (int k = 0; k < 3; ++k) c[k] = mesh.vertices.world_position(t[k]).cast<float>();
        put((c[1] - c[0]).cross(c[2] - c[0]).normalized());
        for (const Eigen::Vector3f& v : c) put(v);
        *p++ = 0;  // attribute byte count
        *p++ = 0;
    }
    return out;
}

}  // namespace anascan::io
