#include "anascan/processing/io/ptx.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "anascan/processing/io/file_bytes.hpp"
#include "text_lines.hpp"

namespace anascan::io {
namespace {

/// Shortest possible point line ("0 0 0 0" and its newline), to bound cols*rows.
constexpr std::uint64_t kMinPointLineBytes = 8;
constexpr std::uint64_t kMaxPoints = std::numeric_limits<std::int32_t>::max();
constexpr double kRotationTolerance = 1e-4;
constexpr double kAffineTolerance = 1e-9;

/// The header of one scan.
struct PtxHeader {
    int cols = 0;
    int rows = 0;
    Eigen::Vector3d position_world_m = Eigen::Vector3d::Zero();
    Pose T_world_scan = Pose::Identity();
};

/// Where the parser is: the reader, the file name and which scan it reads.
struct Cursor {
    text::LineReader reader;
    std::string_view source;
    std::size_t scan_index = 0;

    text::LineRef where() const { return {source, reader.line_number()}; }
    std::string scan_name() const { return "scan " + std::to_string(scan_index); }
};

// The next line as exactly `count` fields, or an error saying `what` was expected.
Expected<text::Fields> next_fields(Cursor& cursor, std::size_t count, std::string_view what) {
    if (!cursor.reader.next()) {
        return text::line_error(
            ErrorCode::kTruncated, cursor.where(),
            "file ends in the header of " + cursor.scan_name() + ": expected " + std::string(what));
    }
    const text::Fields fields = text::split_fields(cursor.reader.line(), text::kBlanks);
    if (fields.count != count) {
        return text::line_error(ErrorCode::kFormat, cursor.where(),
                                "expected " + std::string(what) + " (" + std::to_string(count) +
                                    " numbers), found " + std::to_string(fields.count) + " fields");
    }
    return fields;
}

Expected<int> read_size(Cursor& cursor, std::string_view what) {
    const Expected<text::Fields> fields = next_fields(cursor, 1, what);
    if (!fields) return fail(fields.error());
    const auto value = text::parse_count((*fields)[0], kMaxPoints, cursor.where());
    if (!value) return fail(value.error());
    if (*value == 0)
        return text::line_error(ErrorCode::kFormat, cursor.where(), std::string(what) + " is 0");
    return static_cast<int>(*value);
}

Expected<Eigen::Vector3d> read_vector(Cursor& cursor, std::string_view what) {
    const Expected<text::Fields> fields = next_fields(cursor, 3, what);
    if (!fields) return fail(fields.error());
    std::array<double, 3> v{};
    if (auto ok = text::parse_doubles(*fields, 0, v, cursor.where()); !ok) return fail(ok.error());
    return Eigen::Vector3d(v[0], v[1], v[2]);
}

// The 4x4 matrix M (row-vector convention, translation in the last row): T = M^T.
Expected<Pose> read_transform(Cursor& cursor) {
    Eigen::Matrix4d M;
    int first_line = 0;
    for (int row = 0; row < 4; ++row) {
        const Expected<text::Fields> fields = next_fields(cursor, 4, "a transform row");
        if (!fields) return fail(fields.error());
        std::array<double, 4> v{};
        if (auto ok = text::parse_doubles(*fields, 0, v, cursor.where()); !ok)
            return fail(ok.error());
        M.row(row) = Eigen::RowVector4d(v[0], v[1], v[2], v[3]);
        if (std::abs(v[3] - (row == 3 ? 1.0 : 0.0)) > kAffineTolerance) {
            return text::line_error(
                ErrorCode::kFormat, cursor.where(),
                "the transform's last column must be 0 0 0 1, found " + text::format_exact(v[3]));
        }
        if (row == 0) first_line = cursor.reader.line_number();
    }
    const Eigen::Matrix3d R = M.topLeftCorner<3, 3>().transpose();
    const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (!(error <= kRotationTolerance) || R.determinant() <= 0.0) {
        return text::line_error(ErrorCode::kFormat, {cursor.source, first_line},
                                "the transform's upper 3x3 is not a rotation");
    }
    Pose T = Pose::Identity();
    T.linear() = R;
    T.translation() = M.row(3).head<3>().transpose();
    return orthonormalized(T);
}

// Sizes, scanner position and axes, transform. Sizes are checked against the bytes left.
Expected<PtxHeader> read_header(Cursor& cursor) {
    PtxHeader header;
    const Expected<int> cols = read_size(cursor, "the column count");
    if (!cols) return fail(cols.error());
    const Expected<int> rows = read_size(cursor, "the row count");
    if (!rows) return fail(rows.error());
    header.cols = *cols;
    header.rows = *rows;
    const std::uint64_t points = std::uint64_t(*cols) * std::uint64_t(*rows);
    const std::uint64_t room = (cursor.reader.remaining_bytes() + 1) / kMinPointLineBytes;
    if (points > kMaxPoints || points > room) {
        return text::line_error(ErrorCode::kTruncated, cursor.where(),
                                cursor.scan_name() + " announces " + std::to_string(*cols) + " x " +
                                    std::to_string(*rows) + " points but only " +
                                    std::to_string(cursor.reader.remaining_bytes()) +
                                    " bytes follow");
    }
    const auto position = read_vector(cursor, "the scanner position");
    if (!position) return fail(position.error());
    header.position_world_m = *position;
    for (const char* axis : {"the scanner x axis", "the scanner y axis", "the scanner z axis"}) {
        if (auto ok = read_vector(cursor, axis); !ok) return fail(ok.error());
    }
    const Expected<Pose> T = read_transform(cursor);
    if (!T) return fail(T.error());
    header.T_world_scan = *T;
    return header;
}

// Parses one point line into the cloud; a zero position is a missing return (returns -1).
Expected<std::int32_t> read_point(const text::Fields& fields, bool colors, text::LineRef where,
                                  PointCloud& cloud) {
    std::array<double, 4> v{};
    if (auto ok = text::parse_doubles(fields, 0, v, where); !ok) return fail(ok.error());
    if (v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0) return RangeGrid::kNoSample;
    if (cloud.empty()) cloud.origin_m = text::origin_for(Eigen::Vector3d(v[0], v[1], v[2]));
    Eigen::Vector3f p;
    for (int i = 0; i < 3; ++i) {
        const Expected<float> f = text::to_float(v[i] - cloud.origin_m[i], i + 1, where);
        if (!f) return fail(f.error());
        p[i] = *f;
    }
    const Expected<float> intensity = text::to_float(v[3], 4, where);
    if (!intensity) return fail(intensity.error());
    std::array<std::uint8_t, 3> rgb{};
    for (std::size_t i = 0; colors && i < 3; ++i) {
        const Expected<std::uint8_t> channel = text::parse_channel(fields[4 + i], 5 + i, where);
        if (!channel) return fail(channel.error());
        rgb[i] = *channel;
    }
    if (colors) cloud.colors.push_back(Rgb8{rgb[0], rgb[1], rgb[2]});
    cloud.intensity.push_back(*intensity);
    cloud.positions.push_back(p);
    return static_cast<std::int32_t>(cloud.size() - 1);
}

// Reads cols*rows point lines (column-major) into the scan and its grid.
Expected<void> read_points(Cursor& cursor, const PtxHeader& header, PtxScan& out) {
    const std::size_t total = std::size_t(header.cols) * std::size_t(header.rows);
    out.grid.rows = header.rows;
    out.grid.cols = header.cols;
    out.grid.point_index.assign(total, RangeGrid::kNoSample);
    out.scan.cloud.positions.reserve(total);  // bounded by the file size in read_header
    out.scan.cloud.intensity.reserve(total);
    std::size_t fields_per_line = 0;
    for (std::size_t k = 0; k < total; ++k) {
        if (!cursor.reader.next()) {
            return text::line_error(ErrorCode::kTruncated, cursor.where(),
                                    "file ends after " + std::to_string(k) + " of " +
                                        std::to_string(total) + " points of " + cursor.scan_name());
        }
        const text::Fields fields = text::split_fields(cursor.reader.line(), text::kBlanks);
        if (k == 0 && (fields.count == 4 || fields.count == 7)) fields_per_line = fields.count;
        if (fields.count != fields_per_line) {
            return text::line_error(ErrorCode::kFormat, cursor.where(),
                                    "expected 'x y z intensity [r g b]' (" +
                                        std::to_string(k == 0 ? 4 : fields_per_line) +
                                        " fields), found " + std::to_string(fields.count));
        }
        const auto index = read_point(fields, fields_per_line == 7, cursor.where(), out.scan.cloud);
        if (!index) return fail(index.error());
        const std::size_t col = k / std::size_t(header.rows);
        const std::size_t row = k % std::size_t(header.rows);
        out.grid.point_index[row * std::size_t(header.cols) + col] = *index;
    }
    return {};
}

ScanMetadata make_metadata(const PtxHeader& header, std::string_view source, std::size_t index) {
    ScanMetadata meta;
    meta.id = std::filesystem::path(source).stem().string() + "#" + std::to_string(index);
    meta.device_kind = DeviceKind::kTimeOfFlight;
    meta.T_world_scan = header.T_world_scan;
    // The position line is the registered scanner position in the world frame, or 0 0 0
    // in unregistered files; in both cases the scanner sits at the origin of its points.
    const bool unregistered = header.position_world_m.isZero(0.0);
    meta.sensor_origin_scan_m =
        unregistered ? Eigen::Vector3d::Zero()
                     : Eigen::Vector3d(header.T_world_scan.inverse() * header.position_world_m);
    return meta;
}

}  // namespace

Expected<std::vector<PtxScan>> parse_ptx(std::span<const char> bytes,
                                         std::string_view source_name) {
    Cursor cursor{text::LineReader(bytes, false), source_name};
    std::vector<PtxScan> scans;
    // Each pass reads one scan; a scan starts wherever the previous one's points end.
    for (text::LineReader peek = cursor.reader; peek.next(); peek = cursor.reader) {
        const Expected<PtxHeader> header = read_header(cursor);
        if (!header) return fail(header.error());
        PtxScan scan;
        scan.scan.meta = make_metadata(*header, source_name, cursor.scan_index);
        if (auto ok = read_points(cursor, *header, scan); !ok) return fail(ok.error());
        scans.push_back(std::move(scan));
        ++cursor.scan_index;
    }
    if (scans.empty()) {
        return text::line_error(ErrorCode::kEmpty, cursor.where(), "no scan in the file");
    }
    return scans;
}

Expected<std::vector<PtxScan>> read_ptx(const std::filesystem::path& path) {
    const Expected<std::vector<char>> bytes = read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    return parse_ptx(*bytes, path.filename().string());
}

}  // namespace anascan::io
