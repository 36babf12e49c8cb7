#pragma once
// Builders of small E57 files for the reader's tests: our own clouds, other encodings of
// the point fields, and the page-level edits that hostile files are made of.
#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "anascan/processing/io/e57.hpp"
#include "io/e57/crc32c.hpp"
#include "io/e57/file_writer.hpp"
#include "io/e57/paged_file.hpp"

namespace anascan::io::e57_test {

using e57::FieldKind;
using e57::FieldSpec;
using e57::FieldStream;

/// A gridded scan of `rows` x `cols` cells, every third cell empty, with intensity, colour
/// and a pose. Point k sits at an irregular position so that every float bit matters.
inline E57Scan gridded_scan(int rows, int cols, double shift_m) {
    E57Scan s;
    s.name = "station " + std::to_string(rows);
    s.grid.rows = rows;
    s.grid.cols = cols;
    s.grid.point_index.assign(std::size_t(rows * cols), RangeGrid::kNoSample);
    PointCloud& c = s.scan.cloud;
    for (int cell = 0; cell < rows * cols; ++cell) {
        if (cell % 3 == 1) continue;
        s.grid.point_index[std::size_t(cell)] = std::int32_t(c.size());
        const float k = float(cell);
        c.positions.emplace_back(std::sin(k) * 3.0f + float(shift_m), std::cos(k * 0.7f) * 2.0f,
                                 0.001f * k - 1.0f / 3.0f);
        c.intensity.push_back(k / float(rows * cols) + 1e-7f);
        c.colors.push_back(
            Rgb8{std::uint8_t(cell), std::uint8_t(cell * 7), std::uint8_t(255 - cell)});
    }
    s.scan.meta.T_world_scan = make_pose(
        Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized())),
        Eigen::Vector3d(12.5, -3.25, 1.125));
    return s;
}

/// A field with its stored values packed.
inline FieldStream field(FieldSpec spec, std::span<const std::uint64_t> stored) {
    FieldStream f{.spec = std::move(spec)};
    e57::BitPacker packer(f);
    for (const std::uint64_t v : stored) packer.put(v);
    return f;
}

inline FieldSpec integer_spec(std::string name, std::int64_t lo, std::int64_t hi) {
    return {.name = std::move(name),
            .kind = FieldKind::kInteger,
            .minimum = lo,
            .maximum = hi,
            .bits = e57::bits_for_range(lo, hi)};
}

inline FieldSpec scaled_spec(std::string name, std::int64_t lo, std::int64_t hi, double scale,
                             double offset) {
    FieldSpec s = integer_spec(std::move(name), lo, hi);
    s.kind = FieldKind::kScaledInteger;
    s.scale = scale;
    s.offset = offset;
    return s;
}

inline FieldSpec float_spec(std::string name, bool single) {
    return {.name = std::move(name),
            .kind = FieldKind::kFloat,
            .single_precision = single,
            .bits = single ? 32 : 64};
}

/// The logical bytes of a file (its pages without their checksums).
inline std::vector<std::uint8_t> logical_bytes(std::span<const char> file) {
    std::vector<std::uint8_t> out;
    for (std::size_t page = 0; page + e57::kPageBytes <= file.size(); page += e57::kPageBytes) {
        const auto* p = reinterpret_cast<const std::uint8_t*>(file.data() + page);
        out.insert(out.end(), p, p + e57::kPageDataBytes);
    }
    return out;
}

/// Writes a little-endian integer into logical bytes.
template <class T>
void poke(std::vector<std::uint8_t>& logical, std::size_t at, T value) {
    for (std::size_t i = 0; i < sizeof(T); ++i)
        logical[at + i] = std::uint8_t(std::uint64_t(value) >> (8 * i));
}

}  // namespace anascan::io::e57_test
