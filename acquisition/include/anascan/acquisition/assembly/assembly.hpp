#pragma once
/// \file
/// Assembles scans whose poses are known (a Stanford .conf) into one model and measures
/// how well every overlapping pair agrees. This is the foundation's end-to-end job: it
/// exercises the formats, poses and neighbour search on real data; automatic registration
/// (no known poses) builds on it.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/evaluation/scan_agreement.hpp"
#include "anascan/processing/io/stanford_conf.hpp"

namespace anascan::acquisition {

struct AssemblyConfig {
    double model_voxel_m = 0.0;     ///< Down-sample the merged model (0 keeps every point).
    double min_pair_overlap = 0.1;  ///< Pairs overlapping less than this are not reported.
    bool measure_pairs = true;      ///< False only merges (e.g. `session export`).
    AgreementConfig agreement;
};

struct AssembledScan {
    std::string file;        ///< As named in the .conf.
    std::size_t points = 0;  ///< Finite points used.
    std::size_t non_finite_removed = 0;
};

struct PairReport {
    std::string a, b;  ///< Scan files; figures are of a's samples against b.
    PairAgreement agreement;
};

struct AssemblyReport {
    std::vector<AssembledScan> scans;
    std::vector<PairReport> pairs;        ///< Overlapping pairs, both directions merged (a < b).
    PointCloud model;                     ///< All scans in the common frame.
    double median_pair_distance_m = 0.0;  ///< Median over pairs of their median distance.
    double worst_pair_distance_m = 0.0;   ///< Largest per-pair median distance.
};

/// Progress messages ("loaded bun045.ply (40097 points)") for long work.
using ProgressFn = std::function<void(std::string_view message)>;

/// Loads every `bmesh` scan of the .conf (paths relative to its folder), places it with
/// its pose, measures pairwise agreement and merges the model. Errors name the file.
Expected<AssemblyReport> assemble_from_conf(const std::filesystem::path& conf_path,
                                            const AssemblyConfig& config,
                                            const ProgressFn& progress = {});

/// The same for entries given directly (files relative to `folder`).
Expected<AssemblyReport> assemble_entries(const std::filesystem::path& folder,
                                          std::span<const io::ConfEntry> entries,
                                          const AssemblyConfig& config,
                                          const ProgressFn& progress = {});

/// The report as JSON text (units in the key names), without the model points.
std::string report_to_json(const AssemblyReport& report);

}  // namespace anascan::acquisition
