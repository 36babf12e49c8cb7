#pragma once
/// \file
/// `.xf` files: a 4x4 rigid transform as 16 whitespace-separated numbers, row-major (four
/// lines of four), as written by Scanalyze and read by MeshLab.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/pose.hpp"

namespace anascan::io {

/// Parses a 4x4 matrix. The last row must be 0 0 0 1 and the upper 3x3 a rotation within
/// 1e-4 (it is then re-orthonormalised); errors name the line.
Expected<Pose> parse_xf(std::span<const char> bytes, std::string_view source_name);

/// Reads an .xf file.
Expected<Pose> read_xf(const std::filesystem::path& path);

/// Formats a pose as four lines of four numbers with round-trip precision.
std::string format_xf(const Pose& T);

/// Writes an .xf file crash-safely.
Expected<void> write_xf(const std::filesystem::path& path, const Pose& T);

}  // namespace anascan::io
