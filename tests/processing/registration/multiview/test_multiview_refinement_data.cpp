// Multi-view refinement of the ten Stanford bunny scans: bun.conf poses perturbed by 1° and
// 2 mm (fixed seed), pairwise fine registration of every overlapping pair keeping the final
// correspondences, then eq. 4 over all scans; every scan must end within 0.5° and 1 mm of
// bun.conf relative to bun000. Skips when ../shared/data is absent.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"
#include "anascan/processing/registration/multiview/multiview_refinement.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "test_normals_util.hpp"

namespace anascan {
namespace {

namespace fs = std::filesystem;

const fs::path kBunnyDir = fs::path(ANASCAN_SHARED_DATA_DIR) / "stanford-bunny-range-scans/data";

struct BunnyScans {
    std::vector<std::string> names;
    std::vector<PointCloud> clouds;  // Scan frames, with normals toward +z.
    std::vector<Pose> T_world_scan_conf;
};

std::unique_ptr<BunnyScans> load_bunny() {
    auto conf = io::read_conf(kBunnyDir / "bun.conf");
    if (!conf) return nullptr;
    auto scans = std::make_unique<BunnyScans>();
    for (const io::ConfEntry& entry : conf->entries) {
        auto ply = io::read_ply(kBunnyDir / entry.file);
        if (!ply) return nullptr;
        // The Cyberware scanner looks from +z of each scan frame (see test_normals_util).
        test::estimate_normals_pca(ply->cloud, Eigen::Vector3f::UnitZ());
        scans->names.push_back(entry.file);
        scans->clouds.push_back(std::move(ply->cloud));
        scans->T_world_scan_conf.push_back(entry.T_world_scan);
    }
    return scans;
}

// bun.conf moved by 1° about a random axis through each scan's world centroid and by 2 mm
// in a random direction.
std::vector<Pose> perturbed(const BunnyScans& scans, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<Pose> poses;
    for (std::size_t s = 0; s < scans.clouds.size(); ++s) {
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (std::size_t i = 0; i < scans.clouds[s].size(); ++i) {
            centroid += scans.clouds[s].world_position(i);
        }
        centroid = scans.T_world_scan_conf[s] * (centroid / scans.clouds[s].size());
        const Eigen::Vector3d axis(g(rng), g(rng), g(rng));
        const Eigen::Vector3d dir(g(rng), g(rng), g(rng));
        const Eigen::AngleAxisd turn(std::numbers::pi / 180.0, axis.normalized());
        poses.push_back(Eigen::Translation3d(0.002 * dir.normalized()) *
                        Eigen::Translation3d(centroid) * turn * Eigen::Translation3d(-centroid) *
                        scans.T_world_scan_conf[s]);
    }
    return poses;
}

// Pairwise fine registration of every pair from the perturbed poses; pairs that converge
// with enough overlap become links with their final correspondences.
std::vector<MultiviewLink> pairwise_links(const BunnyScans& scans, const std::vector<Pose>& poses) {
    std::vector<std::unique_ptr<KdTree>> trees;
    for (const PointCloud& cloud : scans.clouds) {
        trees.push_back(std::make_unique<KdTree>(cloud.positions));
    }
    std::vector<MultiviewLink> links;
    for (std::size_t j = 0; j < poses.size(); ++j) {
        for (std::size_t k = j + 1; k < poses.size(); ++k) {
            const FineRegistrationResult r =
                register_fine(scans.clouds[k], scans.clouds[j], *trees[j],
                              poses[j].inverse() * poses[k], {.keep_correspondences = true});
            const bool usable = (r.status == FineRegistrationStatus::kConverged ||
                                 r.status == FineRegistrationStatus::kMaxIterations) &&
                                r.overlap_fraction >= 0.25;
            std::printf("pair %-12s <- %-12s %-20s overlap %.2f rms %.3f mm %s\n",
                        scans.names[j].c_str(), scans.names[k].c_str(),
                        std::string(to_string(r.status)).c_str(), r.overlap_fraction, r.rms_m * 1e3,
                        usable ? "link" : "-");
            if (usable) links.push_back({j, k, r.correspondences});
        }
    }
    return links;
}

PoseDifference max_error_to_conf(const BunnyScans& scans, const std::vector<Pose>& poses) {
    PoseDifference worst;
    for (std::size_t s = 0; s < poses.size(); ++s) {
        const PoseDifference e =
            pose_difference(scans.T_world_scan_conf[0].inverse() * scans.T_world_scan_conf[s],
                            poses[0].inverse() * poses[s]);
        std::printf("  %-12s %.4f deg %.4f mm\n", scans.names[s].c_str(), e.rotation_deg,
                    e.translation_m * 1e3);
        worst.rotation_deg = std::max(worst.rotation_deg, e.rotation_deg);
        worst.translation_m = std::max(worst.translation_m, e.translation_m);
    }
    return worst;
}

TEST(MultiviewRefinementBunny, TenScansEndWithinHalfDegreeOneMillimetreOfConf) {
    if (!fs::exists(kBunnyDir / "bun.conf")) {
        GTEST_SKIP() << "Stanford bunny scans not found at " << kBunnyDir
                     << " (they come with ../shared/data beside the checkout)";
    }
    const std::unique_ptr<BunnyScans> scans = load_bunny();
    ASSERT_TRUE(scans != nullptr) << "cannot read the bunny scans in " << kBunnyDir;
    ASSERT_EQ(scans->clouds.size(), 10u);
    const std::vector<Pose> initial = perturbed(*scans, 2024);
    std::printf("initial errors:\n");
    const PoseDifference before = max_error_to_conf(*scans, initial);
    const std::vector<MultiviewLink> links = pairwise_links(*scans, initial);
    const MultiviewRefinementResult r = refine_multiview(initial, links, {});
    for (std::size_t l = 0; l < links.size(); ++l) {
        std::printf("link %zu <- %zu: %zu corr, rms %.3f -> %.3f mm%s\n", links[l].target_index,
                    links[l].source_index, r.links[l].correspondence_count,
                    r.links[l].rms_before_m * 1e3, r.links[l].rms_after_m * 1e3,
                    r.links[l].dropped ? " DROPPED" : "");
    }
    std::printf("final errors:\n");
    const PoseDifference after = max_error_to_conf(*scans, r.T_world_scan);
    std::printf(
        "%zu links, %s, %d rounds, %.1f ms; max error %.3f deg %.3f mm -> %.4f deg "
        "%.4f mm\n",
        links.size(), std::string(to_string(r.status)).c_str(), r.rounds, r.time_s * 1e3,
        before.rotation_deg, before.translation_m * 1e3, after.rotation_deg,
        after.translation_m * 1e3);
    EXPECT_TRUE(r.status == MultiviewStatus::kConverged || r.status == MultiviewStatus::kMaxRounds)
        << to_string(r.status);
    EXPECT_TRUE(r.disconnected_scans.empty());
    EXPECT_LT(after.rotation_deg, 0.5);
    EXPECT_LT(after.translation_m, 0.001);
}

}  // namespace
}  // namespace anascan
