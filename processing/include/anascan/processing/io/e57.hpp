#pragma once
/// \file
/// ASTM E57 (E2807) import and export: the exchange format of terrestrial laser scanners.
///
/// Reading: the 1024-byte pages are checked against their CRC-32C, the XML section is
/// parsed, and each data3D entry becomes one scan: its compressed vector of points is
/// decoded (bitPackCodec; Integer, ScaledInteger and Float fields; Cartesian or spherical
/// coordinates; intensity, colour, row and column indices, invalid states) and its pose
/// becomes meta.T_world_scan. The scanner sits at the origin of its scan's frame, so
/// meta.sensor_origin_scan_m is 0 0 0 and its world position is the pose's translation.
/// Scans with rowIndex and columnIndex also get their range grid, like PTX.
///
/// Hostile input: every error names the file and the byte offset; lengths, offsets and
/// record counts are checked against the file before anything is allocated for them, so
/// memory stays within a small multiple of the file size. See docs/e57.md.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/range_grid.hpp"
#include "anascan/processing/core/scan.hpp"

namespace anascan::io {

/// One scan (a data3D entry) of an E57 file.
struct E57Scan {
    /// Points in the scan's own frame (metres); meta.T_world_scan is the scan's pose in the
    /// file frame, absent when the file gives none; meta.sensor_origin_scan_m is 0 0 0.
    Scan scan;
    RangeGrid grid;    ///< rows x cols from rowIndex/columnIndex; 0 x 0 when not gridded.
    std::string name;  ///< The data3D name ("pumpA").
    std::string guid;
    std::uint64_t record_count = 0;   ///< Point records in the file.
    std::uint64_t invalid_count = 0;  ///< Records dropped: invalid state set, or not finite.
};

/// The scans of an E57 file.
struct E57File {
    std::string guid;
    std::vector<E57Scan> scans;
    std::size_t image_count = 0;  ///< images2D entries (listed, not read).
};

/// Parses E57 bytes; `source_name` starts every error ("pump.e57: byte 2048: ...").
/// kEmpty when the file holds no scan.
Expected<E57File> parse_e57(std::span<const char> bytes, std::string_view source_name);

/// Reads an E57 file.
Expected<E57File> read_e57(const std::filesystem::path& path);

/// Encodes scans as an E57 file: positions as 64-bit Float (origin_m + local position),
/// intensity as 32-bit Float, colour as 8-bit Integer, row and column indices when the
/// grid is set, and the pose when meta.T_world_scan is. Reading it back gives the same
/// points, attributes, grid and pose bit for bit (for clouds within 1 km of their origin).
/// kInvalidArgument when a cloud's attributes are inconsistent or a grid does not match it.
Expected<std::vector<char>> encode_e57(std::span<const E57Scan> scans);

/// Writes scans to an E57 file crash-safely (write_file_atomically).
Expected<void> write_e57(const std::filesystem::path& path, std::span<const E57Scan> scans);

}  // namespace anascan::io
