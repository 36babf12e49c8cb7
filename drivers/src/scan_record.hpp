#pragma once
// One recorded scan: scans/NNNNNN.ply (points) and scans/NNNNNN.json (metadata).

#include <filesystem>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/scan.hpp"

namespace anascan::drivers {

/// Writes the points, then the metadata (each crash-safely); index names the files.
Expected<void> write_scan_record(const std::filesystem::path& folder, std::size_t index,
                                 const Scan& scan);

/// The complete records (those whose .json exists), in index order.
std::vector<std::filesystem::path> list_scan_records(const std::filesystem::path& folder);

/// Reads the record whose metadata file is `json_path`; errors name the file.
Expected<Scan> read_scan_record(const std::filesystem::path& json_path);

}  // namespace anascan::drivers
