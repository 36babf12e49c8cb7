#pragma once
/// \file
/// The last scan as the scanner saw it, for the device panel: a small range image (the
/// points' directions from the sensor, near bright, far dark). The capture session offers no
/// camera image; this one costs reading the saved scan once, off the UI thread. Pure CPU:
/// any thread.

#include <cstdint>
#include <vector>

#include "anascan/processing/core/scan.hpp"

namespace anascan::gui {

struct ScanPreview {
    std::int64_t seq = -1;
    int width_px = 0, height_px = 0;
    std::vector<std::uint8_t> rgb;  ///< width × height × 3, rows top to bottom.
    std::size_t points = 0;         ///< Points of the scan.
};

/// Projects the scan's points, seen from its sensor origin (the scan frame's origin when
/// unknown), onto an angular grid around their mean direction, `width_px` wide and as high
/// as the field of view needs (at most as high as wide); each pixel keeps its nearest point,
/// grey from 255 (nearest) to 70 (farthest); no point: dark blue-grey. An empty scan gives
/// an empty preview (width 0).
ScanPreview make_scan_preview(const Scan& scan, int width_px = 160);

}  // namespace anascan::gui
