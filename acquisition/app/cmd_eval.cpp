// anascan eval POSES.conf --truth TRUTH.conf: per-scan pose errors against ground truth.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>

#include "anascan/processing/evaluation/pose_evaluation.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "commands.hpp"
#include "scan_preparation.hpp"

namespace anascan::cli {
namespace {

struct EvalOptions {
    std::string estimated;
    std::string truth;
    double max_rotation_deg = -1.0;    // < 0: no limit
    double max_translation_mm = -1.0;  // < 0: no limit
    bool at_centroid = false;
};

std::vector<NamedPose> read_named_poses(const std::string& path) {
    auto conf = io::read_conf(path);
    if (!conf) fail_command(conf.error());
    std::vector<NamedPose> poses;
    for (const io::ConfEntry& e : conf->entries) poses.push_back({e.file, e.T_world_scan});
    return poses;
}

/// Centroid (scan frame, metres) of the finite points of the scan named in a .conf.
Eigen::Vector3d scan_centroid(const std::string& conf_path, const std::string& name) {
    const std::string path = (std::filesystem::path(conf_path).parent_path() / name).string();
    auto cloud = load_ply_cloud(path);
    if (!cloud) fail_command(cloud.error());
    remove_non_finite(*cloud);
    if (cloud->empty()) throw CommandFailed(path + ": no finite points to take a centroid of");
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : cloud->positions) sum += p.cast<double>();
    return cloud->origin_m + sum / static_cast<double>(cloud->size());
}

void print_evaluation(const PoseEvaluation& eval) {
    std::printf("reference scan: %s\n", eval.reference.c_str());
    std::printf("%-24s %14s %18s\n", "scan", "rotation deg", "translation mm");
    for (const ScanPoseError& s : eval.scans) {
        if (!s.placed) {
            std::printf("%-24s %14s %18s\n", s.name.c_str(), "not placed", "-");
            continue;
        }
        std::printf("%-24s %14.4f %18.4f\n", s.name.c_str(), s.rotation_deg, 1e3 * s.translation_m);
    }
    for (const std::string& u : eval.unknown) std::printf("%-24s not in the truth\n", u.c_str());
    std::printf("placed %zu of %zu; max rotation error %.4f deg, max translation error %.4f mm\n",
                eval.placed, eval.scans.size(), eval.max_rotation_deg,
                1e3 * eval.max_translation_m);
}

bool shares_a_name(const std::vector<NamedPose>& a, const std::vector<NamedPose>& b) {
    for (const NamedPose& x : a)
        for (const NamedPose& y : b)
            if (x.name == y.name) return true;
    return false;
}

/// The poses renamed to their file names, when those are unique in the list.
std::optional<std::vector<NamedPose>> by_file_name(std::vector<NamedPose> poses) {
    std::set<std::string> seen;
    for (NamedPose& p : poses) {
        p.name = std::filesystem::path(p.name).filename().string();
        if (!seen.insert(p.name).second) return std::nullopt;
    }
    return poses;
}

/// The estimated poses under the truth's names: as they are when they share a name,
/// else matched by file name (a .conf names scans relative to its own folder).
std::vector<NamedPose> match_names(const EvalOptions& o, std::vector<NamedPose> estimated,
                                   std::vector<NamedPose>& truth) {
    if (shares_a_name(estimated, truth)) return estimated;
    auto est = by_file_name(estimated);
    auto tru = by_file_name(truth);
    if (!est || !tru || !shares_a_name(*est, *tru)) {
        throw CommandFailed(o.estimated + " and " + o.truth +
                            " share no scan name, even by file name (first: '" +
                            (estimated.empty() ? "" : estimated[0].name) + "' and '" +
                            (truth.empty() ? "" : truth[0].name) + "')");
    }
    std::printf(
        "matched by file name (the two .conf files name the scans by different "
        "paths, e.g. '%s' and '%s')\n",
        estimated.empty() ? "" : estimated[0].name.c_str(),
        truth.empty() ? "" : truth[0].name.c_str());
    truth = std::move(*tru);
    return std::move(*est);
}

void run_eval(const EvalOptions& o) {
    std::vector<NamedPose> truth = read_named_poses(o.truth);
    if (o.at_centroid) {
        for (NamedPose& t : truth) t.measure_at_scan_m = scan_centroid(o.truth, t.name);
    }
    const std::vector<NamedPose> estimated = match_names(o, read_named_poses(o.estimated), truth);
    const auto eval = evaluate_poses(estimated, truth);
    if (!eval) throw CommandFailed(o.estimated + " and " + o.truth + " share no scan name");
    print_evaluation(*eval);
    const bool all_placed = eval->placed == eval->scans.size();
    const bool rotation_ok = o.max_rotation_deg < 0 || eval->max_rotation_deg <= o.max_rotation_deg;
    const bool translation_ok =
        o.max_translation_mm < 0 || 1e3 * eval->max_translation_m <= o.max_translation_mm;
    if ((o.max_rotation_deg >= 0 || o.max_translation_mm >= 0) &&
        !(all_placed && rotation_ok && translation_ok)) {
        throw CommandFailed("the poses exceed the given limits or miss scans");
    }
}

}  // namespace

void add_eval_command(CLI::App& app) {
    auto opts = std::make_shared<EvalOptions>();
    auto* cmd = app.add_subcommand(
        "eval",
        "Compare estimated poses with ground truth: per-scan rotation error (deg) and "
        "translation error (mm), both sets expressed in the first common scan's frame");
    cmd->add_option("poses", opts->estimated, "Estimated poses (.conf)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--truth", opts->truth, "Ground-truth poses (.conf)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--max-rotation-deg", opts->max_rotation_deg,
                    "Exit with status 1 when a rotation error exceeds this (degrees)");
    cmd->add_option("--max-translation-mm", opts->max_translation_mm,
                    "Exit with status 1 when a translation error exceeds this (mm)");
    cmd->add_flag("--at-centroid", opts->at_centroid,
                  "Measure each translation error at the centroid of the scan's points (the "
                  "scans named in the truth .conf, relative to its folder) instead of at the "
                  "scan frame's origin, which may lie far from the data");
    cmd->callback([opts] { run_eval(*opts); });
}

}  // namespace anascan::cli
