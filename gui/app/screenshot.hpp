#pragma once
/// \file
/// Writes the current back buffer as a PNG (read before the swap: under Mesa/Xvfb the
/// front buffer reads back black, see docs/devices.md).

#include <filesystem>

#include "anascan/processing/core/expected.hpp"

namespace anascan::field {

/// Reads width × height pixels of the back buffer and writes them as an RGB PNG (libpng,
/// not OpenCV's imgcodecs: under ThreadSanitizer, imgcodecs' GDAL plugin reported a lock
/// order inversion inside GDAL, and it brings 84 libraries to the start of the app); the
/// error names the file.
Expected<void> write_screenshot(const std::filesystem::path& path, int width_px, int height_px);

}  // namespace anascan::field
