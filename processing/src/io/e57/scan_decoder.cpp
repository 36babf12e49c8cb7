#include "scan_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "bytestreams.hpp"
#include "io/text_lines.hpp"

namespace anascan::io::e57 {
namespace {

constexpr std::size_t kAbsent = std::size_t(-1);
constexpr std::uint64_t kMinGridCellCap = std::uint64_t(1) << 22;
constexpr std::uint64_t kGridCellsPerPoint = 64;

/// Which prototype field holds which quantity (kAbsent when the scan lacks it).
struct Roles {
    std::array<std::size_t, 3> position{kAbsent, kAbsent, kAbsent};
    bool spherical = false;
    std::size_t invalid = kAbsent, intensity = kAbsent, intensity_invalid = kAbsent;
    std::array<std::size_t, 3> color{kAbsent, kAbsent, kAbsent};
    std::size_t color_invalid = kAbsent, row = kAbsent, column = kAbsent;
};

std::size_t find(const std::vector<FieldSpec>& fields, std::string_view name) {
    for (std::size_t i = 0; i < fields.size(); ++i)
        if (fields[i].name == name) return i;
    return kAbsent;
}

Expected<Roles> find_roles(const PagedFile& file, const ScanSpec& spec) {
    const auto& f = spec.points.fields;
    Roles r;
    r.position = {find(f, "cartesianX"), find(f, "cartesianY"), find(f, "cartesianZ")};
    r.invalid = find(f, "cartesianInvalidState");
    if (std::ranges::find(r.position, kAbsent) != r.position.end()) {
        r.spherical = true;
        r.position = {find(f, "sphericalRange"), find(f, "sphericalAzimuth"),
                      find(f, "sphericalElevation")};
        r.invalid = find(f, "sphericalInvalidState");
    }
    if (std::ranges::find(r.position, kAbsent) != r.position.end()) {
        return fail(file.error_at(ErrorCode::kUnsupported, spec.points.physical_offset,
                                  "scan '" + spec.name +
                                      "': neither cartesianX/Y/Z nor sphericalRange/Azimuth/"
                                      "Elevation fields"));
    }
    r.intensity = find(f, "intensity");
    r.intensity_invalid = find(f, "isIntensityInvalid");
    r.color = {find(f, "colorRed"), find(f, "colorGreen"), find(f, "colorBlue")};
    if (std::ranges::find(r.color, kAbsent) != r.color.end()) r.color = {kAbsent, kAbsent, kAbsent};
    r.color_invalid = find(f, "isColorInvalid");
    r.row = find(f, "rowIndex");
    r.column = find(f, "columnIndex");
    if (r.row == kAbsent || r.column == kAbsent) r.row = r.column = kAbsent;
    return r;
}

double at(const std::vector<double>& v, std::size_t i) { return i == kAbsent ? 0.0 : v[i]; }

// A grid index as an integer: -1 when negative or not a number, clipped far beyond any cap.
std::int64_t to_index(double v) {
    if (!(v >= 0.0)) return -1;
    return v > 1e12 ? std::int64_t(1e12) : std::int64_t(v);
}

Eigen::Vector3d position_of(const Roles& r, const std::vector<double>& v) {
    const Eigen::Vector3d p(v[r.position[0]], v[r.position[1]], v[r.position[2]]);
    if (!r.spherical) return p;
    const double range = p[0], azimuth = p[1], elevation = p[2];
    return {range * std::cos(elevation) * std::cos(azimuth),
            range * std::cos(elevation) * std::sin(azimuth), range * std::sin(elevation)};
}

/// The colour scale: colorLimits, else the colour field's own range, else 0..255.
std::pair<double, double> color_range(const ScanSpec& spec, const Roles& r) {
    if (spec.has_color_limits) return {spec.color_minimum, spec.color_maximum};
    if (r.color[0] == kAbsent) return {0.0, 255.0};
    const FieldSpec& red = spec.points.fields[r.color[0]];
    if (red.kind == FieldKind::kInteger && red.maximum > red.minimum)
        return {double(red.minimum), double(red.maximum)};
    return {0.0, 255.0};
}

std::uint8_t to_channel(double value, std::pair<double, double> range) {
    const double unit = (value - range.first) / (range.second - range.first);
    return std::uint8_t(std::lround(std::clamp(unit, 0.0, 1.0) * 255.0));
}

/// The decoder's state: one bit reader per field and the scan being built.
struct Decoder {
    const ScanSpec& spec;
    Roles roles;
    std::pair<double, double> colors;
    std::vector<BitReader> readers;
    std::vector<double> values;
    std::vector<std::array<std::int64_t, 2>> cells;  ///< row, column of each kept point
    E57Scan out;
};

// Appends record `values` to the scan unless it is invalid.
void keep_record(Decoder& d) {
    const Roles& r = d.roles;
    const Eigen::Vector3d p = position_of(r, d.values);
    PointCloud& cloud = d.out.scan.cloud;
    const Eigen::Vector3d origin =
        cloud.empty() && p.allFinite() ? text::origin_for(p) : cloud.origin_m;
    const Eigen::Vector3f local = (p - origin).cast<float>();  // inf beyond the float range
    if (at(d.values, r.invalid) != 0.0 || !local.allFinite()) {
        ++d.out.invalid_count;
        return;
    }
    if (cloud.empty()) cloud.origin_m = origin;
    cloud.positions.push_back(local);
    if (r.intensity != kAbsent) {
        const bool valid = at(d.values, r.intensity_invalid) == 0.0;
        cloud.intensity.push_back(valid ? float(d.values[r.intensity]) : 0.0f);
    }
    if (r.color[0] != kAbsent) {
        const bool valid = at(d.values, r.color_invalid) == 0.0;
        const auto c = [&](int k) {
            return valid ? to_channel(d.values[r.color[k]], d.colors) : 0;
        };
        cloud.colors.push_back(Rgb8{std::uint8_t(c(0)), std::uint8_t(c(1)), std::uint8_t(c(2))});
    }
    if (r.row != kAbsent)
        d.cells.push_back({to_index(d.values[r.row]), to_index(d.values[r.column])});
}

Expected<void> build_grid(const PagedFile& file, Decoder& d) {
    if (d.roles.row == kAbsent || d.cells.empty()) return {};
    std::int64_t rows = 0, cols = 0;
    for (const auto& [row, col] : d.cells) {
        if (row < 0 || col < 0) {
            return fail(file.error_at(ErrorCode::kFormat, d.spec.points.physical_offset,
                                      "scan '" + d.spec.name + "': negative row or column index"));
        }
        rows = std::max(rows, row + 1);
        cols = std::max(cols, col + 1);
    }
    const std::uint64_t cap = std::max(kMinGridCellCap, kGridCellsPerPoint * d.cells.size());
    if (std::uint64_t(rows) > cap || std::uint64_t(cols) > cap / std::uint64_t(rows)) {
        return fail(file.error_at(ErrorCode::kFormat, d.spec.points.physical_offset,
                                  "scan '" + d.spec.name + "': grid of " + std::to_string(rows) +
                                      " x " + std::to_string(cols) + " cells for " +
                                      std::to_string(d.cells.size()) + " points"));
    }
    RangeGrid& grid = d.out.grid;
    grid.rows = int(rows);
    grid.cols = int(cols);
    grid.point_index.assign(std::size_t(rows * cols), RangeGrid::kNoSample);
    for (std::size_t i = 0; i < d.cells.size(); ++i) {
        std::int32_t& cell = grid.point_index[std::size_t(d.cells[i][0] * cols + d.cells[i][1])];
        if (cell == RangeGrid::kNoSample) cell = std::int32_t(i);  // first return wins
    }
    return {};
}

ScanMetadata make_metadata(const PagedFile& file, const ScanSpec& spec, std::size_t index) {
    ScanMetadata meta;
    meta.id = std::filesystem::path(file.source()).stem().string() + "#" + std::to_string(index);
    meta.device_kind = DeviceKind::kTimeOfFlight;
    meta.T_world_scan = spec.T_file_scan;
    meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
    return meta;
}

}  // namespace

Expected<E57Scan> decode_scan(const PagedFile& file, const ScanSpec& spec, std::size_t index) {
    const std::string what = "scan '" + spec.name + "'";
    auto roles = find_roles(file, spec);
    if (!roles) return fail(roles.error());
    auto streams = read_bytestreams(file, spec.points, what);
    if (!streams) return fail(streams.error());
    Decoder d{.spec = spec, .roles = *roles, .colors = color_range(spec, *roles)};
    for (const auto& s : *streams) d.readers.emplace_back(s);
    d.values.resize(spec.points.fields.size());
    const std::size_t n = std::size_t(spec.points.record_count);  // fits: checked in the section
    d.out.scan.cloud.positions.reserve(n);
    for (std::size_t k = 0; k < n; ++k) {
        for (std::size_t i = 0; i < d.values.size(); ++i)
            d.values[i] = next_value(spec.points.fields[i], d.readers[i]);
        keep_record(d);
    }
    if (d.out.scan.cloud.size() > std::size_t(std::numeric_limits<std::int32_t>::max())) {
        return fail(file.error_at(ErrorCode::kUnsupported, spec.points.physical_offset,
                                  what + ": more than 2^31 points"));
    }
    if (auto ok = build_grid(file, d); !ok) return fail(ok.error());
    d.out.scan.meta = make_metadata(file, spec, index);
    d.out.name = spec.name;
    d.out.guid = spec.guid;
    d.out.record_count = spec.points.record_count;
    return std::move(d.out);
}

}  // namespace anascan::io::e57
