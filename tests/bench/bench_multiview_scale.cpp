// Memory and convergence of the multi-view stage alone at scale (not a test, not in CI):
// a chain of N scans along x, 0.0667 m apart like the windows of bench_register_scale, each
// linked to the next and every 16th also to the one after it (1 062 links at 1000 scans, as
// in the full benchmark), each link with C exact correspondences on a bumpy surface with
// tilted normals; every scan but the first starts off its true pose by a rotation of 1 mrad about
// the world origin and about 1 mm. Prints how much the peak resident set (VmHWM) rose during
// refine_multiview, the time, the status, rounds, and the largest remaining error; runs in about a
// second, where the full benchmark takes 15-30 min.
//
//   anascan_bench_multiview_scale [--scans 1000] [--correspondences 50]
//       [--tikhonov 1e-10] [--rounds 15] [--default-allocator]
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "anascan/processing/core/allocator.hpp"
#include "anascan/processing/registration/multiview/multiview_refinement.hpp"

namespace {

using namespace anascan;

constexpr double kStepM = 0.2 / 3.0;

struct Options {
    std::size_t scans = 1000;
    std::size_t correspondences = 50;
    double tikhonov = MultiviewRefinementConfig{}.tikhonov_relative;
    int rounds = MultiviewRefinementConfig{}.max_rounds;
    bool default_allocator = false;
};

bool parse(int argc, char** argv, Options& o) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const char* value = i + 1 < argc ? argv[i + 1] : "0";
        if (a == "--scans") {
            o.scans = std::strtoul(value, nullptr, 10), ++i;
        } else if (a == "--correspondences") {
            o.correspondences = std::strtoul(value, nullptr, 10), ++i;
        } else if (a == "--tikhonov") {
            o.tikhonov = std::strtod(value, nullptr), ++i;
        } else if (a == "--rounds") {
            o.rounds = std::atoi(value), ++i;
        } else if (a == "--default-allocator") {
            o.default_allocator = true;
        } else {
            std::fprintf(stderr,
                         "usage: %s [--scans N] [--correspondences C] [--tikhonov T] "
                         "[--rounds R] [--default-allocator]\n",
                         argv[0]);
            return false;
        }
    }
    return o.scans >= 2 && o.correspondences >= 10;
}

// A field of /proc/self/status in megabytes ("VmHWM", "VmRSS").
double status_mb(const std::string& key) {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0.0;
    char line[256];
    double kb = 0.0;
    while (std::fgets(line, sizeof line, f)) {
        if (std::string(line).rfind(key + ":", 0) == 0) {
            std::sscanf(line + key.size() + 1, "%lf", &kb);
        }
    }
    std::fclose(f);
    return kb / 1024.0;
}

// Resets VmHWM to the current resident set (Linux: "5" to clear_refs).
void reset_high_water() {
    if (std::FILE* f = std::fopen("/proc/self/clear_refs", "w")) {
        std::fputs("5", f);
        std::fclose(f);
    }
}

MultiviewLink chain_link(std::size_t target, std::size_t source, std::size_t count,
                         const std::vector<Pose>& truth, std::mt19937& rng) {
    std::uniform_real_distribution<double> along(0.0, 0.13), across(-0.1, 0.1);
    std::normal_distribution<double> gauss(0.0, 1.0);
    MultiviewLink link{.target_index = target, .source_index = source, .correspondences = {}};
    link.correspondences.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        const Eigen::Vector3d world(kStepM * double(source) + along(rng), across(rng),
                                    0.005 * gauss(rng));
        const Eigen::Vector3d normal =
            Eigen::Vector3d(0.5 * gauss(rng), 0.5 * gauss(rng), 1.0).normalized();
        link.correspondences.push_back(
            {.source_point_m = truth[source].inverse() * world,
             .target_point_m = truth[target].inverse() * world,
             .target_normal = (truth[target].linear().transpose() * normal).cast<float>()});
    }
    return link;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    if (!parse(argc, argv, o)) return 2;
    if (!o.default_allocator) use_fixed_mmap_threshold();
    std::mt19937 rng(1);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::vector<Pose> truth(o.scans, Pose::Identity()), initial(o.scans);
    for (std::size_t s = 0; s < o.scans; ++s) {
        truth[s].translation() = Eigen::Vector3d(kStepM * double(s), 0.0, 0.0);
        Pose offset = Pose::Identity();
        const Eigen::Vector3d axis = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
        offset.linear() = Eigen::AngleAxisd(1e-3, axis.normalized()).toRotationMatrix();
        offset.translation() = 1e-3 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
        initial[s] = s == 0 ? truth[s] : Pose(offset * truth[s]);
    }
    std::vector<MultiviewLink> links;
    for (std::size_t s = 0; s + 1 < o.scans; ++s) {
        links.push_back(chain_link(s, s + 1, o.correspondences, truth, rng));
        if (s % 16 == 0 && s + 2 < o.scans)
            links.push_back(chain_link(s, s + 2, o.correspondences, truth, rng));
    }
    const double before_mb = status_mb("VmRSS");
    reset_high_water();
    const MultiviewRefinementResult r =
        refine_multiview(initial, links, {.max_rounds = o.rounds, .tikhonov_relative = o.tikhonov});
    const double rise_mb = status_mb("VmHWM") - before_mb;
    const auto largest_error_mm = [&](const std::vector<Pose>& poses) {
        double error_m = 0.0;
        for (std::size_t s = 0; s < o.scans; ++s) {
            error_m = std::max(error_m, (poses[s].translation() - truth[s].translation()).norm());
        }
        return 1e3 * error_m;
    };
    std::printf("scans %zu, links %zu of %zu correspondences, tikhonov %.1e, %s\n", o.scans,
                links.size(), o.correspondences, o.tikhonov,
                o.default_allocator ? "default allocator" : "fixed mmap threshold");
    std::printf("multi-view: %s after %d rounds, %.2f s, pivot ratio %.2e\n",
                std::string(to_string(r.status)).c_str(), r.rounds, r.time_s, r.pivot_ratio);
    std::printf("resident before %.1f MB, peak rose by %.1f MB during refine_multiview\n",
                before_mb, rise_mb);
    std::printf("largest translation error %.3g mm (at the start %.3g mm)\n",
                largest_error_mm(r.T_world_scan), largest_error_mm(initial));
    return 0;
}
