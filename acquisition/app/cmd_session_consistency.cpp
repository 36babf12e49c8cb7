// anascan session consistency DIR: the scans of a session's model checked against each other
// in their stored poses (the check the live registrar runs after each refinement).
#include <cstdio>

#include "anascan/acquisition/assembly/group_pulls.hpp"
#include "anascan/acquisition/store/groups.hpp"
#include "commands.hpp"
#include "register_consistency.hpp"
#include "session_cli.hpp"

namespace anascan::cli {
namespace {

struct ConsistencyOptions {
    std::string dir;
    bool pairs = false;
};

/// Each scan of every group against the rest of its group at once: the pulled ones (all
/// with `all`).
void print_group_pulls(const acquisition::SessionStore& store, bool all) {
    auto pulls = acquisition::group_pulls(store);
    if (!pulls) fail_command(pulls.error());
    std::size_t pulled = 0;
    for (const acquisition::GroupPull& g : *pulls) {
        const ScanPull& p = g.pull;
        pulled += p.pulled;
        if (all || p.pulled)
            std::printf(
                "scan %lld of group %d %s by its other %zu scans: %.3f mm, %.4f deg "
                "(rms %.3f -> %.3f mm, overlap %.0f %%, %d rounds)\n",
                static_cast<long long>(g.seq), g.group, p.pulled ? "PULLED" : "held",
                g.group_scans - 1, p.moved_m * 1e3, p.rotation_deg, p.rms_before_m * 1e3,
                p.rms_m * 1e3, 100.0 * p.overlap_fraction, p.rounds);
    }
    std::printf(
        "each scan against the rest of its group (groups of 3 or more): %zu pulled "
        "away%s\n",
        pulled, pulled ? ": slid along a face (anascan session register DIR --scan N)" : "");
}

void run_consistency(const ConsistencyOptions& o) {
    auto store = open_session(o.dir, acquisition::SessionOpenMode::kReadOnly);
    auto records = store->scans();
    if (!records) fail_command(records.error());
    const int group = acquisition::largest_group(*records);
    std::vector<PointCloud> clouds;
    std::vector<ConsistencyScan> scans;
    std::vector<std::string> names;
    for (const acquisition::ScanRecord& r : *records) {
        if (!acquisition::counts_in_group(r) || r.group != group) continue;
        auto scan = store->load_scan(r.seq);
        if (!scan) fail_command(scan.error());
        const auto sensor = r.sensor_origin_scan_m.value_or(Eigen::Vector3d::Zero());
        clouds.push_back(reduce_for_consistency(scan->cloud, sensor));
        names.push_back("scan " + std::to_string(r.seq));
    }
    std::size_t k = 0;
    for (const acquisition::ScanRecord& r : *records) {
        if (!acquisition::counts_in_group(r) || r.group != group) continue;
        scans.push_back(
            {.cloud = &clouds[k++],
             .T_group_scan = *r.pose,
             .sensor_origin_scan_m = r.sensor_origin_scan_m.value_or(Eigen::Vector3d::Zero())});
    }
    const GroupConsistency result = check_group_consistency(scans, {});
    std::printf(
        "group %d: %zu scans, %zu overlapping pairs, %zu disagree; %s\n", group, scans.size(),
        result.pairs.size(),
        static_cast<std::size_t>(std::count_if(result.pairs.begin(), result.pairs.end(),
                                               [](const PairConsistency& p) { return !p.agrees; })),
        result.consistent ? "consistent" : "NOT consistent");
    if (o.pairs) print_pairs(result, names);
    for (std::size_t i : result.take_out) {
        const auto& worst = result.scans[i].worst_pair;
        std::printf("take out %s: %s\n", names[i].c_str(),
                    worst ? describe(result.pairs[*worst], names).c_str() : "?");
    }
    print_group_pulls(*store, o.pairs);
}

}  // namespace

void add_session_consistency_command(CLI::App& session) {
    auto o = std::make_shared<ConsistencyOptions>();
    auto* cmd = session.add_subcommand(
        "consistency",
        "Check the scans of the session's model against each other in their stored poses "
        "(crossing normals, free space, overlap angle) and name those that contradict it; "
        "then each scan of every group against the rest of its group at once (a scan slid "
        "along a face moves back)");
    cmd->add_option("dir", o->dir, "Session folder")->required();
    cmd->add_flag("--pairs", o->pairs, "Print every overlapping pair's figures");
    cmd->callback([o] { run_consistency(*o); });
}

}  // namespace anascan::cli
