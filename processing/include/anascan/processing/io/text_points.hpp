#pragma once
/// \file
/// Plain-text point lists: XYZ (`x y z [nx ny nz] [r g b]` or `x y z [intensity] [r g b]`)
/// and Leica PTS (first line the point count, then `x y z intensity [r g b]`).
/// Separators: spaces, tabs or commas; `#` and `//` start comments; blank lines ignored.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::io {

/// Parses XYZ text. The column count of the first data line fixes the layout:
/// 3 = xyz, 4 = xyz+intensity, 6 = xyz+normals (or xyz+rgb when the last three are
/// integers 0-255 other than an axis-aligned unit normal such as `0 0 1`), 7 =
/// xyz+intensity+rgb, 9 = xyz+normals+rgb. Every later line must have the same count;
/// errors name the line. A first point further than 1 km from 0 sets `origin_m` (rounded
/// to metres) so that float positions keep their precision (docs/text-formats.md).
Expected<PointCloud> parse_xyz(std::span<const char> bytes, std::string_view source_name);

/// Parses PTS text: the first non-comment line is the point count, which must match; then
/// `x y z intensity [r g b]` lines (`x y z [r g b]` without intensity is also read).
Expected<PointCloud> parse_pts(std::span<const char> bytes, std::string_view source_name);

/// Reads `.xyz`/`.txt`/`.asc` as XYZ and `.pts` as PTS (by extension).
Expected<PointCloud> read_text_points(const std::filesystem::path& path);

/// XYZ text, one point per line: `x y z` in world metres (`origin_m` added, 6 decimals),
/// then `nx ny nz` when the cloud has normals, or else the intensity, then `r g b`; the
/// layout parse_xyz reads back. Confidence is not written.
std::string serialize_xyz(const PointCloud& cloud);

/// Writes serialize_xyz(cloud) to `path` atomically (errors name the file).
Expected<void> write_xyz(const std::filesystem::path& path, const PointCloud& cloud);

}  // namespace anascan::io
