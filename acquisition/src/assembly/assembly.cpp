#include "anascan/acquisition/assembly/assembly.hpp"

#include <algorithm>

#include "anascan/processing/cleaning/normals.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"

namespace anascan::acquisition {
namespace {

struct PlacedScan {
    std::string file;
    PointCloud cloud;  // In the common frame.
};

Expected<PlacedScan> load_placed(const std::filesystem::path& folder, const io::ConfEntry& entry,
                                 AssembledScan& info) {
    auto ply = io::read_ply(folder / entry.file);
    if (!ply) return fail(ply.error());
    info.file = entry.file;
    info.non_finite_removed = remove_non_finite(ply->cloud);
    info.points = ply->cloud.size();
    if (ply->cloud.empty()) {
        return fail(ErrorCode::kEmpty, (folder / entry.file).string() + ": no finite points");
    }
    // Normals make the agreement point-to-plane; their sign does not matter there.
    if (!ply->cloud.has_normals()) estimate_normals(ply->cloud, {});
    return PlacedScan{entry.file, transformed(ply->cloud, entry.T_world_scan)};
}

// Symmetric figures of a pair: the direction with more overlap speaks for the pair.
PairAgreement symmetric(const PairAgreement& ab, const PairAgreement& ba) {
    return ab.overlap_fraction >= ba.overlap_fraction ? ab : ba;
}

void measure_pairs(const std::vector<PlacedScan>& scans, const AssemblyConfig& config,
                   AssemblyReport& report) {
    std::vector<KdTree> trees;
    trees.reserve(scans.size());
    for (const PlacedScan& s : scans) trees.emplace_back(s.cloud.positions);
    for (std::size_t i = 0; i < scans.size(); ++i) {
        for (std::size_t j = i + 1; j < scans.size(); ++j) {
            const PairAgreement ab =
                measure_agreement(scans[i].cloud, scans[j].cloud, trees[j], config.agreement);
            const PairAgreement ba =
                measure_agreement(scans[j].cloud, scans[i].cloud, trees[i], config.agreement);
            const PairAgreement pair = symmetric(ab, ba);
            if (pair.overlap_fraction < config.min_pair_overlap) continue;
            report.pairs.push_back({scans[i].file, scans[j].file, pair});
        }
    }
}

void summarise_pairs(AssemblyReport& report) {
    std::vector<double> medians;
    for (const PairReport& p : report.pairs) medians.push_back(p.agreement.median_distance_m);
    if (medians.empty()) return;
    report.worst_pair_distance_m = *std::max_element(medians.begin(), medians.end());
    auto middle = medians.begin() + medians.size() / 2;
    std::nth_element(medians.begin(), middle, medians.end());
    report.median_pair_distance_m = *middle;
}

}  // namespace

Expected<AssemblyReport> assemble_from_conf(const std::filesystem::path& conf_path,
                                            const AssemblyConfig& config,
                                            const ProgressFn& progress) {
    auto conf = io::read_conf(conf_path);
    if (!conf) return fail(conf.error());
    if (conf->entries.empty()) {
        return fail(ErrorCode::kEmpty,
                    conf_path.string() + ": no 'bmesh' lines, nothing to assemble");
    }
    return assemble_entries(conf_path.parent_path(), conf->entries, config, progress);
}

Expected<AssemblyReport> assemble_entries(const std::filesystem::path& folder,
                                          std::span<const io::ConfEntry> entries,
                                          const AssemblyConfig& config,
                                          const ProgressFn& progress) {
    AssemblyReport report;
    std::vector<PlacedScan> scans;
    for (const io::ConfEntry& entry : entries) {
        AssembledScan info;
        auto placed = load_placed(folder, entry, info);
        if (!placed) return fail(placed.error());
        if (progress)
            progress("loaded " + entry.file + " (" + std::to_string(info.points) + " points)");
        report.scans.push_back(info);
        scans.push_back(std::move(*placed));
    }
    if (config.measure_pairs) {
        if (progress) progress("measuring agreement of " + std::to_string(scans.size()) + " scans");
        measure_pairs(scans, config, report);
        summarise_pairs(report);
    }
    for (const PlacedScan& s : scans) append(report.model, s.cloud);
    if (config.model_voxel_m > 0.0) {
        report.model = voxel_downsample(report.model, {.voxel_size_m = config.model_voxel_m});
    }
    return report;
}

}  // namespace anascan::acquisition
