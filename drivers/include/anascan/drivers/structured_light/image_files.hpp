#pragma once
/// \file
/// Captured image sequences on disk: shell globs in natural order, parallel grey loading.

#include <filesystem>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers::sl {

/// Natural order: digit runs compare as numbers ("im2" < "im10"), the rest byte-wise.
bool natural_less(std::string_view a, std::string_view b);

/// The regular files matching a shell glob (`dir/pattern_cam1_*.jpg`), naturally sorted.
/// kIo error naming the pattern when nothing matches.
Expected<std::vector<std::filesystem::path>> glob_natural(const std::string& pattern);

/// Reads every file as 8-bit grey (`decode_grey_image`: JPEG or PNG; JPEG decodes only the
/// luma), in parallel with TBB, into one block of memory. `on_loaded(done)` runs after each
/// file, from worker threads. The error names the first file that cannot be read (kIo) or
/// decoded (kFormat).
Expected<std::vector<cv::Mat>> load_grey_images(
    std::span<const std::filesystem::path> files,
    const std::function<void(std::size_t done)>& on_loaded = {});

}  // namespace anascan::drivers::sl
