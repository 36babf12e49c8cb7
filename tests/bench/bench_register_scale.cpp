// Scale benchmark of register_scans (not a test, not in CI): N synthetic scans of P points,
// windows along a long bumpy wall, each in a random frame, registered with pair pruning
// and the out-of-core store; prints peak memory (getrusage ru_maxrss), time per stage and
// the error of every placed scan against its known pose.
//
//   anascan_bench_register_scale --scans 100 [--points 50000] [--candidates 3]
//       [--voxel-mm 2] [--max-loaded 8] [--link-correspondences 50] [--spill DIR]
//       [--all-in-memory] [--list] [--max-failures 2] [--bridge-rounds 4] [--seed 1]
//       [--default-allocator] [--multiview-tikhonov 1e-10]
//
// By default the benchmark fixes glibc's mmap threshold (use_fixed_mmap_threshold, as the
// register command does); --default-allocator keeps glibc's dynamic threshold.
//
// The wall: z = Σ h exp(−|xy − c|²/2w²) over x in [0, L], |y| <= 0.1 m, bumps 3-12 mm high
// and 6-16 mm wide, 1500 per m² (test_bumpy_surface.hpp has 350: too flat between bumps. Window k
// spans x in [k s, k s + 0.2 m] with s = 0.2/3 m (each window overlaps two neighbours on each
// side), sampled on a square grid with `points` points, 0.1 mm Gaussian noise in z, no
// normals (estimated toward the sensor, 1 m above the window), moved by a uniform random
// rotation and up to 0.5 m. Scans are generated inside their loaders, one at a time.
#include <sys/resource.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "anascan/processing/core/allocator.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/evaluation/pose_sampling.hpp"
#include "anascan/processing/registration/batch/scan_registration.hpp"
#include "peak_memory.hpp"

namespace {

using namespace anascan;
using namespace anascan::bench;

constexpr double kWindowM = 0.2;
constexpr double kStepM = kWindowM / 3.0;
constexpr double kBumpsPerM2 = 1500.0;
constexpr double kCellM = 0.05;  // Bump lookup cells along x.

struct Options {
    std::size_t scans = 100;
    std::size_t points = 50000;
    std::size_t candidates = 3;
    double voxel_mm = 2.0;
    std::size_t max_loaded = 8;
    std::size_t link_correspondences = 50;  // compress_link: the optimum of all of them.
    std::size_t max_failures = 2;
    std::size_t bridge_rounds = 4;
    std::string spill;
    bool in_memory = false;
    bool list = false;
    bool default_allocator = false;  ///< --default-allocator: glibc's dynamic mmap threshold.
    unsigned seed = 1;
    double multiview_tikhonov = MultiviewRefinementConfig{}.tikhonov_relative;
};

struct Bump {
    double x, y, h, w;
};

// Bumps of the whole wall, bucketed by x cell.
struct Wall {
    std::vector<std::vector<Bump>> cells;

    explicit Wall(double length_m, unsigned seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> x(0.0, length_m), y(-0.12, 0.12),
            height(0.003, 0.012), width(0.006, 0.016), sign(-1.0, 1.0);
        cells.resize(static_cast<std::size_t>(length_m / kCellM) + 1);
        const auto count = static_cast<std::size_t>(kBumpsPerM2 * length_m * 0.24);
        for (std::size_t i = 0; i < count; ++i) {
            Bump b{x(rng), y(rng), height(rng), width(rng)};
            if (sign(rng) < -0.3) b.h = -b.h;
            cells[std::min(cells.size() - 1, static_cast<std::size_t>(b.x / kCellM))].push_back(b);
        }
    }

    double height(double px, double py) const {
        const auto c = static_cast<long>(px / kCellM);
        double z = 0.0;
        for (long k = std::max(0L, c - 2); k <= c + 2 && k < static_cast<long>(cells.size()); ++k) {
            for (const Bump& b : cells[static_cast<std::size_t>(k)]) {
                const double d2 = (px - b.x) * (px - b.x) + (py - b.y) * (py - b.y);
                if (d2 < 25.0 * b.w * b.w) z += b.h * std::exp(-d2 / (2.0 * b.w * b.w));
            }
        }
        return z;
    }
};

struct View {
    Pose T_scan_object;
    Eigen::Vector3d centroid_object_m;
};

PointCloud window(const Wall& wall, std::size_t k, std::size_t points, unsigned seed) {
    const auto side = static_cast<std::size_t>(std::sqrt(static_cast<double>(points)));
    const double spacing = kWindowM / static_cast<double>(side);
    std::mt19937 rng(seed * 7919u + static_cast<unsigned>(k));
    std::normal_distribution<double> noise(0.0, 0.0001);
    PointCloud cloud;
    cloud.positions.reserve(side * side);
    const double x0 = static_cast<double>(k) * kStepM;
    for (std::size_t i = 0; i < side; ++i) {
        for (std::size_t j = 0; j < side; ++j) {
            const double x = x0 + (static_cast<double>(i) + 0.5) * spacing;
            const double y = -0.1 + (static_cast<double>(j) + 0.5) * spacing;
            cloud.positions.emplace_back(float(x - x0), float(y),
                                         float(wall.height(x, y) + noise(rng)));
        }
    }
    cloud.origin_m = Eigen::Vector3d(x0, 0.0, 0.0);
    return cloud;
}

bool parse(int argc, char** argv, Options& o) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : "0"; };
        if (a == "--scans")
            o.scans = std::strtoul(next(), nullptr, 10);
        else if (a == "--points")
            o.points = std::strtoul(next(), nullptr, 10);
        else if (a == "--candidates")
            o.candidates = std::strtoul(next(), nullptr, 10);
        else if (a == "--voxel-mm")
            o.voxel_mm = std::strtod(next(), nullptr);
        else if (a == "--max-loaded")
            o.max_loaded = std::strtoul(next(), nullptr, 10);
        else if (a == "--link-correspondences")
            o.link_correspondences = std::strtoul(next(), nullptr, 10);
        else if (a == "--spill")
            o.spill = next();
        else if (a == "--all-in-memory")
            o.in_memory = true;
        else if (a == "--list")
            o.list = true;
        else if (a == "--default-allocator")
            o.default_allocator = true;
        else if (a == "--max-failures")
            o.max_failures = std::strtoul(next(), nullptr, 10);
        else if (a == "--bridge-rounds")
            o.bridge_rounds = std::strtoul(next(), nullptr, 10);
        else if (a == "--multiview-tikhonov")
            o.multiview_tikhonov = std::strtod(next(), nullptr);
        else if (a == "--seed")
            o.seed = static_cast<unsigned>(std::strtoul(next(), nullptr, 10));
        else {
            std::fprintf(
                stderr,
                "usage: %s --scans N [--points P] [--candidates K] [--voxel-mm V]\n"
                "  [--max-loaded M] [--link-correspondences C] [--spill DIR]\n"
                "  [--all-in-memory] [--list] [--max-failures F] [--bridge-rounds R] [--seed S]\n"
                "  [--default-allocator] [--multiview-tikhonov T]\n",
                argv[0]);
            return false;
        }
    }
    return o.scans >= 2 && o.points >= 100;
}

struct Errors {
    double max_rotation_deg = 0.0, max_translation_mm = 0.0;
    double max_neighbour_rotation_deg = 0.0, max_neighbour_translation_mm = 0.0;
};

// Error of scan i relative to scan j (estimate against truth), translation at i's centroid.
PoseDifference relative_error(const ScanRegistrationResult& r, const std::vector<View>& views,
                              std::size_t i, std::size_t j, double& translation_m) {
    const Pose truth = views[j].T_scan_object * views[i].T_scan_object.inverse();
    const Pose estimate = r.scans[j].T_world_scan.inverse() * r.scans[i].T_world_scan;
    const Eigen::Vector3d c = views[i].T_scan_object * views[i].centroid_object_m;
    translation_m = (estimate * c - truth * c).norm();
    return pose_difference(estimate, truth);
}

// `position[k]`: where window k sits in the (shuffled) input.
Errors measure(const ScanRegistrationResult& r, const std::vector<View>& views,
               const std::vector<std::size_t>& position, bool list) {
    Errors e;
    const std::size_t ref = r.reference_scan;
    for (std::size_t k = 0; k < position.size(); ++k) {
        const std::size_t i = position[k];
        if (!r.scans[i].placed) {
            if (list)
                std::printf("%s: not placed: %s\n", r.scans[i].name.c_str(),
                            r.scans[i].reason.c_str());
            continue;
        }
        double t = 0.0;
        const PoseDifference d = relative_error(r, views, i, ref, t);
        if (list)
            std::printf("%s: %.4f deg %.4f mm\n", r.scans[i].name.c_str(), d.rotation_deg, t * 1e3);
        e.max_rotation_deg = std::max(e.max_rotation_deg, d.rotation_deg);
        e.max_translation_mm = std::max(e.max_translation_mm, t * 1e3);
        if (k + 1 < position.size() && r.scans[position[k + 1]].placed) {
            const PoseDifference n = relative_error(r, views, i, position[k + 1], t);
            e.max_neighbour_rotation_deg = std::max(e.max_neighbour_rotation_deg, n.rotation_deg);
            e.max_neighbour_translation_mm = std::max(e.max_neighbour_translation_mm, t * 1e3);
        }
    }
    return e;
}

// What happened to the pair of windows a and b (input indices ia, ib): not a candidate,
// no hypotheses, skipped, or the global status.
std::string pair_state(const ScanRegistrationResult& r, std::size_t ia, std::size_t ib) {
    const std::size_t s = std::max(ia, ib), t = std::min(ia, ib);
    for (const PairOutcome& p : r.pairs) {
        if (p.source != s || p.target != t) continue;
        if (p.hypotheses == 0) return "no-hypotheses";
        if (p.global.skipped) return "skipped";
        return std::string(to_string(p.global.status)) + "(score " +
               std::to_string(static_cast<int>(p.match_score)) + ")";
    }
    return "not-candidate";
}

// Prints, for every break of the chain (windows k and k+1 in different groups), what the
// pairs across it gave, and counts the neighbour pairs by outcome.
void report_chain(const ScanRegistrationResult& r, const std::vector<std::size_t>& position) {
    std::size_t breaks = 0;
    for (std::size_t k = 0; k + 1 < position.size(); ++k) {
        const std::size_t a = position[k], b = position[k + 1];
        if (r.scans[a].group == r.scans[b].group) continue;
        ++breaks;
        std::printf("break %zu|%zu (groups %d|%d): ", k, k + 1, r.scans[a].group, r.scans[b].group);
        for (std::size_t lo = k > 0 ? k - 1 : 0; lo <= k; ++lo) {
            for (std::size_t hi = k + 1; hi <= std::min(k + 2, position.size() - 1); ++hi) {
                if (hi - lo > 2) continue;
                std::printf("%zu-%zu %s  ", lo, hi,
                            pair_state(r, position[lo], position[hi]).c_str());
            }
        }
        std::printf("\n");
    }
    std::printf("chain breaks %zu\n", breaks);
}

// The scans of the wall, in a shuffled input order (the registration must not rely on the
// order); `position[k]` is where window k landed.
struct ShuffledScans {
    std::vector<ScanInput> inputs;
    std::vector<View> views;
    std::vector<std::size_t> position;
};

ShuffledScans make_scans(const Options& o, const Wall& wall, std::mt19937& rng) {
    std::vector<View> views;
    std::vector<ScanInput> inputs;
    for (std::size_t k = 0; k < o.scans; ++k) {
        const Pose T_scan_object = sample_random_pose(rng, 0.5);
        const Eigen::Vector3d centre(static_cast<double>(k) * kStepM + 0.5 * kWindowM, 0.0, 0.0);
        views.push_back({T_scan_object, centre});
        inputs.push_back(
            {.name = "window" + std::to_string(k),
             .load =
                 [&wall, k, T_scan_object, o] {
                     return Expected<PointCloud>(
                         transformed(window(wall, k, o.points, o.seed), T_scan_object));
                 },
             .sensor_origin_scan_m = T_scan_object * (centre + Eigen::Vector3d(0, 0, 1.0))});
    }
    std::vector<std::size_t> order(o.scans);
    for (std::size_t i = 0; i < o.scans; ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    ShuffledScans out;
    out.position.resize(o.scans);
    for (std::size_t i : order) {
        out.position[i] = out.inputs.size();
        out.inputs.push_back(inputs[i]);
        out.views.push_back(views[i]);
    }
    return out;
}

ScanRegistrationConfig make_config(const Options& o) {
    ScanRegistrationConfig config{.voxel_size_m = o.voxel_mm * 1e-3,
                                  .max_candidates_per_scan = o.candidates,
                                  .max_loaded_clouds = o.max_loaded,
                                  .max_failed_refinements_per_scan = o.max_failures,
                                  .max_link_correspondences = o.link_correspondences,
                                  .bridge_rounds = o.bridge_rounds};
    config.multiview.tikhonov_relative = o.multiview_tikhonov;
    if (!o.in_memory) {
        config.spill_directory = o.spill.empty() ? std::filesystem::temp_directory_path() /
                                                       ("anascan-scale-" + std::to_string(getpid()))
                                                 : std::filesystem::path(o.spill);
    }
    return config;
}

void print_summary(const Options& o, const ScanRegistrationResult& r, const Errors& e,
                   double total_s) {
    std::printf("scans %zu, points %zu, candidates/scan %zu, voxel %.1f mm, %s\n", o.scans,
                o.points, o.candidates, o.voxel_mm,
                o.in_memory ? "all in memory" : "spilled to disk");
    std::printf(
        "placed %zu of %zu, groups %zu, pairs matched %zu (%zu by bridging), verified %zu, "
        "links %zu (%zu dropped), multiview %s\n",
        r.placed_count, r.scans.size(), r.group_count, r.pairs.size(), r.bridge_pair_count,
        r.verified_pair_count, r.link_count, r.dropped_link_count,
        std::string(to_string(r.multiview_status)).c_str());
    std::printf(
        "stages s: prepare %.1f, features %.1f, matching %.1f, pairwise %.1f, bridging %.1f, "
        "fine %.1f, multiview %.1f, register %.1f, total with generation %.1f\n",
        r.timings.prepare_s, r.timings.features_s, r.timings.matching_s, r.timings.pairwise_s,
        r.timings.bridging_s, r.timings.fine_s, r.timings.multiview_s, r.timings.total_s, total_s);
    std::printf(
        "error vs truth (reference %s): max %.4f deg, %.4f mm at the scan centroids; "
        "neighbours: max %.4f deg, %.4f mm\n",
        r.scans[r.reference_scan].name.c_str(), e.max_rotation_deg, e.max_translation_mm,
        e.max_neighbour_rotation_deg, e.max_neighbour_translation_mm);
}

// Candidate pairs against the truth: windows overlap their two neighbours on each side.
void print_candidates(const ScanRegistrationResult& r, const std::vector<std::size_t>& position) {
    std::vector<std::size_t> window_of(position.size());
    for (std::size_t k = 0; k < position.size(); ++k) window_of[position[k]] = k;
    std::size_t overlapping = 0, wrong_verified = 0;
    for (const PairOutcome& p : r.pairs) {
        const std::size_t a = window_of[p.source], b = window_of[p.target];
        const bool overlap = (a > b ? a - b : b - a) <= 2;
        overlapping += overlap;
        wrong_verified += !overlap && p.verified;
    }
    std::printf(
        "candidate pairs: %zu overlapping of %zu (windows overlap their 2 neighbours "
        "each side: %zu pairs), %zu non-overlapping verified\n",
        overlapping, r.pairs.size(), 2 * position.size() - 3, wrong_verified);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    if (!parse(argc, argv, o)) return 2;
    const bool fixed_mmap = !o.default_allocator && use_fixed_mmap_threshold();
    const Stopwatch watch;
    const Wall wall(static_cast<double>(o.scans + 3) * kStepM + kWindowM, o.seed);
    std::mt19937 rng(o.seed);
    const ShuffledScans scans = make_scans(o, wall, rng);
    const ScanRegistrationConfig config = make_config(o);
    std::size_t messages = 0;
    PeakTrace peaks;
    const ScanRegistrationResult r = register_scans(scans.inputs, config, [&](std::string_view m) {
        peaks.observe(m);
        if (++messages % 200 == 0)
            std::fprintf(stderr, "[%zu] %.*s\n", messages, int(m.size()), m.data());
    });
    if (!config.spill_directory.empty()) {
        std::error_code ignored;
        std::filesystem::remove(config.spill_directory, ignored);
    }
    peaks.observe("end of register_scans");
    const Errors e = measure(r, scans.views, scans.position, o.list);
    if (o.list) report_chain(r, scans.position);
    print_summary(o, r, e, watch.seconds());
    print_candidates(r, scans.position);
    std::printf("peak RSS %.1f MB (%s), cloud reloads %zu%s%s\n", peak_rss_mb(),
                fixed_mmap ? "fixed mmap threshold" : "default allocator", r.cloud_reloads,
                r.spill_error.empty() ? "" : ", spill error: ", r.spill_error.c_str());
    peaks.print();
    return r.spill_error.empty() ? 0 : 1;
}
