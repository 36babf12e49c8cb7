#pragma once
/// \file
/// Terrestrial-scanner import (`e57:/folder`): the station exports (ASTM E57) of a folder,
/// in file-name order; every scan of every file is delivered by capture_scan() as one
/// station with its pose (meta.T_world_scan, absent when the export has none) and its
/// sensor origin (the origin of the scan frame).

#include <filesystem>
#include <memory>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/scanner.hpp"

namespace anascan::drivers {

/// kIo when the folder is missing, kEmpty when it holds no .e57 file. capture_scan()
/// returns the stations one by one, then kEmpty ("no more stations"). A file that is not
/// E57 or is corrupt gives the reader's error (file and byte offset); a station without
/// points is kFormat naming the file and the station; either way the next capture reads
/// the next file, and the stations already delivered are untouched.
Expected<std::unique_ptr<Scanner>> open_e57_station_scanner(const std::filesystem::path& folder);

/// The `e57:` backend (folders are not enumerable).
Backend make_e57_backend();

}  // namespace anascan::drivers
