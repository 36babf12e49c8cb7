#pragma once
/// \file
/// Coverage of a session's stone from its registered scans on disk (the `anascan coverage`
/// command and the figure stored at the end of a capture), and its JSON form.

#include <functional>
#include <nlohmann/json_fwd.hpp>

#include "anascan/acquisition/session_store.hpp"
#include "anascan/processing/coverage.hpp"

namespace anascan::acquisition {

struct SessionCoverageConfig {
    /// Each scan is down-sampled to this voxel edge (metres) before coverage: the criterion
    /// needs density at the coverage's own scale, not every point.
    double voxel_size_m = 0.001;
    CoverageConfig coverage{};
};

/// Coverage from the registered, non-excluded scans of the session's largest group, in that
/// group's frame. kEmpty when no scan is registered. `progress(done, total)` may be empty.
Expected<CoverageReport> session_coverage(
    const SessionStore& store, const SessionCoverageConfig& config,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

/// {"fraction", "surface_area_m2", "covered_area_m2", "holes": [{"area_m2", "centre_m",
/// "normal", "samples"}]}.
nlohmann::json coverage_json(const CoverageReport& report);

}  // namespace anascan::acquisition
