#pragma once
/// \file
/// Terrestrial-scanner import (`ptx:/folder`): the station exports (Leica PTX) of a folder,
/// in file-name order, each station delivered by capture_scan() as one scan with its
/// scanner pose (meta.T_world_scan) and sensor origin.

#include <filesystem>
#include <memory>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/scanner.hpp"

namespace anascan::drivers {

/// kIo when the folder is missing, kEmpty when it holds no .ptx file. capture_scan()
/// returns the stations one by one, then kEmpty ("no more stations"); a corrupt file is
/// kFormat/kTruncated naming the file and line.
Expected<std::unique_ptr<Scanner>> open_ptx_station_scanner(const std::filesystem::path& folder);

/// The `ptx:` backend (folders are not enumerable).
Backend make_ptx_backend();

}  // namespace anascan::drivers
