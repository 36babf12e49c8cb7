#pragma once
/// \file
/// Leica PTX import: one or more gridded scans per file, each with its scanner pose.
///
/// Layout per scan: columns, rows, scanner position (3), scanner axes (3 lines of 3),
/// a 4x4 transform (4 lines of 4, row vector convention: the last row is the
/// translation), then columns*rows lines `x y z intensity [r g b]` (column-major: all rows
/// of column 0 first). A line `0 0 0 0.5` (zero position) marks a missing return.
///
/// The position line is read as the registered scanner position in the world frame (or
/// 0 0 0 when unregistered); meta.sensor_origin_scan_m is it expressed in the scan frame,
/// i.e. 0 0 0 for standard files. See docs/text-formats.md.

#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/range_grid.hpp"
#include "anascan/processing/core/scan.hpp"

namespace anascan::io {

/// One station of a PTX file.
struct PtxScan {
    Scan scan;       ///< Points in the scanner frame; meta.T_world_scan from the header.
    RangeGrid grid;  ///< rows x cols; kNoSample where the scanner got no return.
};

/// Parses every scan in PTX text; errors name the line.
Expected<std::vector<PtxScan>> parse_ptx(std::span<const char> bytes, std::string_view source_name);

/// Reads a PTX file.
Expected<std::vector<PtxScan>> read_ptx(const std::filesystem::path& path);

}  // namespace anascan::io
