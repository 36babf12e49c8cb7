#pragma once
/// \file
/// A folder of terrestrial-scanner station exports as a scanner: the files of one format
/// in file-name order, each station delivered by capture_scan() as one scan. The PTX and
/// E57 backends differ only in the file format they read.

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/scanner.hpp"

namespace anascan::drivers {

/// One export format: its URI scheme, file extension and reader.
struct StationFormat {
    std::string scheme;     ///< "ptx", "e57".
    std::string extension;  ///< ".ptx", ".e57" (matched case-insensitively).
    std::string model;      ///< DeviceInfo::model, e.g. "PTX station exports".
    /// The stations of one file, in the scan frame with their poses when the file has them.
    std::function<Expected<std::vector<Scan>>(const std::filesystem::path&)> read;
};

/// kIo when the folder is missing, kEmpty when it holds no file of the format.
/// capture_scan() returns the stations one by one, then kEmpty ("no more stations"); a
/// corrupt file is the reader's error naming the file; the next capture reads the next file.
Expected<std::unique_ptr<Scanner>> open_station_export_scanner(const std::filesystem::path& folder,
                                                               StationFormat format);

/// The backend that opens `SCHEME:/folder` with open_station_export_scanner (folders are
/// not enumerable).
Backend make_station_export_backend(StationFormat format, std::string description);

}  // namespace anascan::drivers
