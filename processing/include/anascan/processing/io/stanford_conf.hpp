#pragma once
/// \file
/// Stanford `.conf` scan-alignment files: `bmesh FILE tx ty tz qx qy qz qw` per scan
/// (`camera ...` lines are read and kept, other keywords are errors).
///
/// Convention (verified numerically on bun.conf, see ../shared/data/README.txt): with
/// q = qw + qx i + qy j + qz k, a point p of FILE maps into the common frame as
/// p_world = R(q)^T p + t.  So T_world_scan has rotation R(q)^T and translation t.

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/pose.hpp"

namespace anascan::io {

/// One `bmesh` line.
struct ConfEntry {
    std::string file;   ///< As written in the file (relative to the .conf's folder).
    Pose T_world_scan;  ///< Maps the file's points into the common frame.
};

struct StanfordConf {
    std::optional<Pose> camera;      ///< The `camera` line, same convention, if any.
    std::vector<ConfEntry> entries;  ///< In file order.

    /// The entry for `file` (exact match), or nullptr.
    const ConfEntry* find(std::string_view file) const;
};

/// Parses .conf text; errors name the line. Quaternions are normalised; a quaternion of
/// near-zero norm, a duplicate file name or a non-finite number is an error.
Expected<StanfordConf> parse_conf(std::span<const char> bytes, std::string_view source_name);

/// Reads a .conf file.
Expected<StanfordConf> read_conf(const std::filesystem::path& path);

/// Formats .conf text with enough digits that poses round-trip to 1e-12.
std::string format_conf(const StanfordConf& conf);

/// Writes a .conf file crash-safely.
Expected<void> write_conf(const std::filesystem::path& path, const StanfordConf& conf);

}  // namespace anascan::io
