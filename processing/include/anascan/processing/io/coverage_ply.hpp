#pragma once
/// \file
/// The coverage samples as a coloured point cloud file (green observed, yellow sparse, red
/// unobserved), binary PLY with normals and colours, written crash-safely.

#include <filesystem>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/coverage/coverage.hpp"

namespace anascan::io {

/// Writes `report.samples` to `path`; kEmpty when the report has no samples, the writer's
/// error (naming the file) otherwise.
Expected<void> write_coverage_ply(const std::filesystem::path& path, const CoverageReport& report);

}  // namespace anascan::io
