#pragma once
/// \file
/// Clouds for the view until the capture session is attached: PLY files from the command
/// line, or a synthetic stone (for measuring the renderer at a chosen point count).

#include <filesystem>
#include <vector>

#include "anascan/gui/field_view_state.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::field {

/// A cloud and its scan-list row.
struct LoadedScan {
    gui::ScanRow row;
    PointCloud cloud;
};

/// Reads one PLY as a scan with sequence number seq (error names the file).
Expected<LoadedScan> load_ply_scan(const std::filesystem::path& path, std::int64_t seq);

struct SyntheticStoneConfig {
    std::size_t points = 2'000'000;  ///< In total.
    int scans = 10;                  ///< Chunks, each seen from one side of the stone.
    double size_x_m = 0.8, size_y_m = 0.5, size_z_m = 0.4;
};

/// A rough box-shaped stone (points on its faces with 1 mm noise, fixed seed), split into
/// `scans` chunks by the azimuth they face, with plausible registration figures.
std::vector<LoadedScan> synthetic_stone(const SyntheticStoneConfig& config);

}  // namespace anascan::field
