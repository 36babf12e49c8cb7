#include "anascan/processing/io/text_points.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>

#include "anascan/processing/io/file_bytes.hpp"
#include "text_lines.hpp"

namespace anascan::io {
namespace {

/// Shortest possible point line ("0 0 0" and its newline), to bound a PTS count.
constexpr std::uint64_t kMinPointLineBytes = 6;

/// Which columns a file has; fixed by its first data line.
struct Layout {
    std::size_t fields = 3;
    bool intensity = false;
    bool normals = false;
    bool colors = false;
    int first_line = 1;
};

// Three integer fields 0-255 that are not an axis-aligned unit normal such as "0 0 1".
bool looks_like_rgb(const text::Fields& fields, std::size_t first) {
    unsigned sum = 0;
    for (std::size_t i = first; i < first + 3; ++i) {
        if (!text::is_color_channel(fields[i])) return false;
        unsigned channel = 0;
        std::from_chars(fields[i].data(), fields[i].data() + fields[i].size(), channel);
        sum += channel;
    }
    return sum != 1;
}

Expected<Layout> xyz_layout(const text::Fields& fields, text::LineRef where) {
    Layout layout{.fields = fields.count, .first_line = where.line};
    switch (fields.count) {
        case 3:
            return layout;
        case 4:
            layout.intensity = true;
            return layout;
        case 6:
            layout.colors = looks_like_rgb(fields, 3);
            layout.normals = !layout.colors;
            return layout;
        case 7:
            layout.intensity = layout.colors = true;
            return layout;
        case 9:
            layout.normals = layout.colors = true;
            return layout;
        default:
            return text::line_error(ErrorCode::kFormat, where,
                                    "expected 3, 4, 6, 7 or 9 fields (x y z [...]), found " +
                                        std::to_string(fields.count));
    }
}

Expected<Layout> pts_layout(const text::Fields& fields, text::LineRef where) {
    Layout layout{.fields = fields.count, .first_line = where.line};
    switch (fields.count) {
        case 3:
            return layout;
        case 4:
            layout.intensity = true;
            return layout;
        case 6:
            layout.colors = true;
            return layout;
        case 7:
            layout.intensity = layout.colors = true;
            return layout;
        default:
            return text::line_error(ErrorCode::kFormat, where,
                                    "expected 'x y z intensity [r g b]' (3, 4, 6 or 7 fields), "
                                    "found " +
                                        std::to_string(fields.count));
    }
}

Expected<Eigen::Vector3f> to_float3(const Eigen::Vector3d& v, std::size_t first_field,
                                    text::LineRef where) {
    Eigen::Vector3f out;
    for (int i = 0; i < 3; ++i) {
        const Expected<float> f = text::to_float(v[i], first_field + i, where);
        if (!f) return fail(f.error());
        out[i] = *f;
    }
    return out;
}

// Appends the point of one data line to `cloud`, checking it against `layout`.
Expected<void> add_point(const text::Fields& fields, const Layout& layout, text::LineRef where,
                         PointCloud& cloud) {
    if (fields.count != layout.fields) {
        return text::line_error(ErrorCode::kFormat, where,
                                "expected " + std::to_string(layout.fields) +
                                    " fields (as on line " + std::to_string(layout.first_line) +
                                    "), found " + std::to_string(fields.count));
    }
    std::array<double, 6> v{};
    const std::size_t numbers = layout.normals ? 6 : (layout.intensity ? 4 : 3);
    if (auto ok = text::parse_doubles(fields, 0, std::span(v).first(numbers), where); !ok) {
        return fail(ok.error());
    }
    if (cloud.empty()) cloud.origin_m = text::origin_for(Eigen::Vector3d(v[0], v[1], v[2]));
    const auto position = to_float3(Eigen::Vector3d(v[0], v[1], v[2]) - cloud.origin_m, 1, where);
    if (!position) return fail(position.error());
    if (layout.intensity) {
        const Expected<float> intensity = text::to_float(v[3], 4, where);
        if (!intensity) return fail(intensity.error());
        cloud.intensity.push_back(*intensity);
    }
    if (layout.normals) {
        const auto normal = to_float3(Eigen::Vector3d(v[3], v[4], v[5]), 4, where);
        if (!normal) return fail(normal.error());
        cloud.normals.push_back(*normal);
    }
    if (layout.colors) {
        std::array<std::uint8_t, 3> rgb{};
        for (std::size_t i = 0; i < 3; ++i) {
            const std::size_t field = layout.fields - 3 + i;
            const Expected<std::uint8_t> channel =
                text::parse_channel(fields[field], field + 1, where);
            if (!channel) return fail(channel.error());
            rgb[i] = *channel;
        }
        cloud.colors.push_back(Rgb8{rgb[0], rgb[1], rgb[2]});
    }
    cloud.positions.push_back(*position);
    return {};
}

void reserve(const Layout& layout, std::size_t count, PointCloud& cloud) {
    cloud.positions.reserve(count);
    if (layout.intensity) cloud.intensity.reserve(count);
    if (layout.normals) cloud.normals.reserve(count);
    if (layout.colors) cloud.colors.reserve(count);
}

Unexpected<Error> no_points(std::string_view source, const text::LineReader& reader) {
    return text::line_error(ErrorCode::kEmpty, {source, reader.line_number()},
                            "end of file without any point");
}

// Reads the PTS count line; bounds it by the bytes left so a lying count cannot allocate.
Expected<std::uint64_t> read_pts_count(text::LineReader& reader, std::string_view source) {
    if (!reader.next()) return no_points(source, reader);
    const text::LineRef where{source, reader.line_number()};
    const text::Fields fields = text::split_fields(reader.line(), text::kBlanksAndCommas);
    if (fields.count != 1) {
        return text::line_error(ErrorCode::kFormat, where,
                                "expected the point count alone on the first line, found " +
                                    std::to_string(fields.count) + " fields");
    }
    const auto count = text::parse_count(fields[0], std::uint64_t{1} << 40, where);
    if (!count) return fail(count.error());
    if (*count == 0) return text::line_error(ErrorCode::kEmpty, where, "point count is 0");
    if (*count > (reader.remaining_bytes() + 1) / kMinPointLineBytes) {
        return text::line_error(ErrorCode::kTruncated, where,
                                "count announces " + std::to_string(*count) + " points but only " +
                                    std::to_string(reader.remaining_bytes()) + " bytes follow");
    }
    return *count;
}

}  // namespace

Expected<PointCloud> parse_xyz(std::span<const char> bytes, std::string_view source_name) {
    PointCloud cloud;
    text::LineReader reader(bytes, true);
    Layout layout;
    while (reader.next()) {
        const text::LineRef where{source_name, reader.line_number()};
        const text::Fields fields = text::split_fields(reader.line(), text::kBlanksAndCommas);
        if (cloud.empty()) {
            const Expected<Layout> first = xyz_layout(fields, where);
            if (!first) return fail(first.error());
            layout = *first;
        }
        if (auto ok = add_point(fields, layout, where, cloud); !ok) return fail(ok.error());
    }
    if (cloud.empty()) return no_points(source_name, reader);
    return cloud;
}

Expected<PointCloud> parse_pts(std::span<const char> bytes, std::string_view source_name) {
    text::LineReader reader(bytes, true);
    const Expected<std::uint64_t> count = read_pts_count(reader, source_name);
    if (!count) return fail(count.error());
    const int count_line = reader.line_number();
    PointCloud cloud;
    Layout layout;
    while (reader.next()) {
        const text::LineRef where{source_name, reader.line_number()};
        const text::Fields fields = text::split_fields(reader.line(), text::kBlanksAndCommas);
        if (cloud.size() == *count) {
            return text::line_error(ErrorCode::kFormat, where,
                                    "more points than the count " + std::to_string(*count) +
                                        " on line " + std::to_string(count_line));
        }
        if (cloud.empty()) {
            const Expected<Layout> first = pts_layout(fields, where);
            if (!first) return fail(first.error());
            layout = *first;
            reserve(layout, *count, cloud);
        }
        if (auto ok = add_point(fields, layout, where, cloud); !ok) return fail(ok.error());
    }
    if (cloud.size() != *count) {
        return text::line_error(ErrorCode::kTruncated, {source_name, reader.line_number()},
                                "file ends after " + std::to_string(cloud.size()) + " of " +
                                    std::to_string(*count) + " points (count on line " +
                                    std::to_string(count_line) + ")");
    }
    return cloud;
}

Expected<PointCloud> read_text_points(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const bool is_pts = extension == ".pts";
    if (!is_pts && extension != ".xyz" && extension != ".txt" && extension != ".asc") {
        return fail(ErrorCode::kUnsupported,
                    path.string() + ": not a point-list extension (.xyz, .txt, .asc or .pts)");
    }
    const Expected<std::vector<char>> bytes = read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    const std::string name = path.filename().string();
    return is_pts ? parse_pts(*bytes, name) : parse_xyz(*bytes, name);
}

}  // namespace anascan::io
