// The block-assembly figures of docs/reassembly.md on the simulated monument:
//   anascan_assembly_figures fig15|fig15-anathyrosis [SECTION] [MONUMENT_SEED] [STEP_MM]
//     two neighbours of the lowest course (their joint faces flat, or with the simulated
//     anathyrosis) from the Horn placement, three rows: without
//     constraints, with non-penetration only, with non-penetration, co-planarity and
//     co-linearity;
//   anascan_assembly_figures wall N SEEDS [SECTION] [MONUMENT_SEED] [STEP_MM]
//     N = 3 (c0b0, c0b1, c1b0) or 4 (+ c1b1) blocks started 5° and 20 mm off the truth, over
//     SEEDS random starts: every block's error and the penetration.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "anascan/processing/core/stopwatch.hpp"
#include "monument_assembly.hpp"

namespace {

using namespace anascan;
using namespace anascan::sim::testing;

// Worst block error of an assembly, and the dense check.
struct Outcome {
    BlockError worst;
    ra::AssemblyCheck check;
    int iterations = 0;
    double seconds = 0.0;
    std::string status;
};

Outcome run(const MonumentAssembly& m, const std::vector<Pose>& start,
            const ra::AssemblyConfig& c) {
    const Stopwatch watch;
    auto r = ra::assemble_blocks(m.problem, start, c);
    Outcome o;
    o.seconds = watch.seconds();
    if (!r) {
        o.status = r.error().message;
        return o;
    }
    o.status = ra::to_string(r->status);
    o.iterations = r->iterations;
    for (std::size_t b = 1; b < m.problem.blocks.size(); ++b) {
        const BlockError e = block_error(m, r->T_world_block, b);
        o.worst.rotation_deg = std::max(o.worst.rotation_deg, e.rotation_deg);
        o.worst.translation_m = std::max(o.worst.translation_m, e.translation_m);
    }
    o.check = ra::check_assembly(m.problem, r->T_world_block);
    return o;
}

void print(const char* label, const Outcome& o) {
    double gap = 0.0;
    for (const auto& cc : o.check.contacts) gap = std::max(gap, cc.gap_median_m);
    std::printf(
        "%-34s %-14s rot %7.3f deg  trans %7.2f mm  pen max %6.3f mean %6.3f mm (%zu pts)  "
        "median gap %5.2f mm  %2d it  %.2f s\n",
        label, o.status.c_str(), o.worst.rotation_deg, 1e3 * o.worst.translation_m,
        1e3 * o.check.penetration_max_m, 1e3 * o.check.penetration_mean_m,
        o.check.penetrating_points, 1e3 * gap, o.iterations, o.seconds);
}

int fig15(const std::string& section, std::uint64_t seed, double step_m, bool flat) {
    auto m = monument_assembly(section, seed, {"c0b0", "c0b1"}, step_m, flat);
    if (!m) return std::fprintf(stderr, "%s\n", m.error().message.c_str()), 1;
    auto placed = ra::initial_placement(m->problem);
    if (!placed) return std::fprintf(stderr, "%s\n", placed.error().message.c_str()), 1;
    const std::vector<Pose>& start = *placed;
    std::printf("%s seed %llu, c0b0 + c0b1, %zu + %zu points, from the Horn placement\n",
                section.c_str(), (unsigned long long)seed, m->problem.blocks[0].points.size(),
                m->problem.blocks[1].points.size());
    print("truth (the check's floor)", run(*m, m->truth, {.max_iterations = 0}));
    print("Horn placement", run(*m, start, {.max_iterations = 0}));
    print("without constraints",
          run(*m, start, {.non_penetration = false, .use_coplanar = false, .use_colinear = false}));
    print("non-penetration only", run(*m, start, {.use_coplanar = false, .use_colinear = false}));
    print("non-penetration + co-planar/linear", run(*m, start, {}));
    return 0;
}

int wall(int n, int seeds, const std::string& section, std::uint64_t seed, double step_m) {
    const int free_iterations = std::getenv("FREE") ? std::atoi(std::getenv("FREE")) : 0;
    const double angle_deg = std::getenv("START_DEG") ? std::atof(std::getenv("START_DEG")) : 5.0;
    const double shift_m =
        std::getenv("START_MM") ? 1e-3 * std::atof(std::getenv("START_MM")) : 0.02;
    std::vector<std::string> ids{"c0b0", "c0b1", "c1b0"};
    if (n >= 4) ids.push_back("c1b1");
    auto m = monument_assembly(section, seed, ids, step_m);
    if (!m) return std::fprintf(stderr, "%s\n", m.error().message.c_str()), 1;
    std::printf(
        "%s seed %llu, %d blocks, %zu pairs, %zu co-planar, %zu co-linear, start 5 deg 20 mm off\n",
        section.c_str(), (unsigned long long)seed, n, m->problem.contacts.size(),
        m->problem.coplanar.size(), m->problem.colinear.size());
    const ra::AssemblyCheck at_truth = ra::check_assembly(m->problem, m->truth);
    for (const auto& cp : at_truth.coplanar)
        std::printf("at the truth: co-planar %s %.3f deg %.2f mm\n", cp.pair.c_str(), cp.angle_deg,
                    1e3 * cp.offset_m);
    for (const auto& cl : at_truth.colinear)
        std::printf("at the truth: co-linear %s %.3f deg %.2f mm\n", cl.pair.c_str(), cl.angle_deg,
                    1e3 * cl.distance_m);
    int good = 0;
    double worst_rot = 0.0, worst_trans = 0.0, worst_pen = 0.0;
    for (int s = 1; s <= seeds; ++s) {
        const Outcome o = run(*m, perturbed_truth(*m, angle_deg, shift_m, unsigned(s)),
                              {.free_iterations = free_iterations});
        print(("start seed " + std::to_string(s)).c_str(), o);
        good += o.worst.rotation_deg <= 0.1 && o.worst.translation_m <= 0.0005 &&
                o.check.penetration_max_m <= 0.0001;
        worst_rot = std::max(worst_rot, o.worst.rotation_deg);
        worst_trans = std::max(worst_trans, o.worst.translation_m);
        worst_pen = std::max(worst_pen, o.check.penetration_max_m);
    }
    std::printf(
        "%d of %d starts within 0.1 deg, 0.5 mm and 0.1 mm penetration; worst %.3f deg, %.2f mm, "
        "penetration %.3f mm\n",
        good, seeds, worst_rot, 1e3 * worst_trans, 1e3 * worst_pen);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "fig15";
    if (mode == "fig15" || mode == "fig15-anathyrosis")
        return fig15(argc > 2 ? argv[2] : "octagon-wall",
                     argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 0,
                     argc > 4 ? std::atof(argv[4]) * 1e-3 : 0.005, mode == "fig15");
    if (mode == "wall" && argc > 3)
        return wall(std::atoi(argv[2]), std::atoi(argv[3]), argc > 4 ? argv[4] : "octagon-wall",
                    argc > 5 ? std::strtoull(argv[5], nullptr, 10) : 0,
                    argc > 6 ? std::atof(argv[6]) * 1e-3 : 0.005);
    std::fprintf(
        stderr,
        "usage: %s fig15 [SECTION] [SEED] [STEP_MM] | wall N SEEDS [SECTION] [SEED] [STEP_MM]\n",
        argv[0]);
    return 2;
}
