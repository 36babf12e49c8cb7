// The block-assembly figures of docs/reassembly.md on the simulated monument:
//   anascan_assembly_figures fig15|fig15-anathyrosis [SECTION] [MONUMENT_SEED] [STEP_MM]
//     two neighbours of the lowest course (their joint faces flat, or with the simulated
//     anathyrosis) from the Horn placement, three rows: without
//     constraints, with non-penetration only, with non-penetration, co-planarity and
//     co-linearity;
//   anascan_assembly_figures wall N SEEDS [SECTION] [MONUMENT_SEED] [STEP_MM]
//     N = 3 (c0b0, c0b1, c1b0) or 4 (+ c1b1) blocks started 5° and 20 mm off the truth, over
//     SEEDS random starts: every block's error and the penetration;
//   anascan_assembly_figures terms N [SECTION] [MONUMENT_SEED] [STEP_MM]
//     the same wall at the truth: each term's residual per link and the first step with
//     all terms, and with each term left out (what pulls the minimum off the truth).
// After an ok end each run also probes whether the pairs fix every block
// (assembly_probe.hpp) and prints what it names; NO_PROBE=1 skips it.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/reassembly/assembly_probe.hpp"
#include "anascan/processing/reassembly/constrained_lsq.hpp"
#include "monument_assembly.hpp"
#include "reassembly/assembly_steps.hpp"

namespace {

using namespace anascan;
using namespace anascan::sim::testing;

// NORMAL=plane: contact rows along the partner face's fitted normal (else vertex normals).
ra::JointNormal joint_normal() {
    const char* n = std::getenv("NORMAL");
    return n && std::string(n) == "plane" ? ra::JointNormal::kFacePlane : ra::JointNormal::kVertex;
}

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
    if (r->status == ra::AssemblyStatus::kOk && !std::getenv("NO_PROBE")) {
        auto d = ra::probe_determinacy(m.problem, *r, c);
        if (d) ra::mark_underdetermined(m.problem, *d, *r);
        for (const std::string& why : r->offending) std::printf("    %s\n", why.c_str());
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
    const ra::JointNormal jn = joint_normal();
    print("without constraints", run(*m, start,
                                     {.joint_normal = jn,
                                      .non_penetration = false,
                                      .use_coplanar = false,
                                      .use_colinear = false}));
    print("non-penetration only",
          run(*m, start, {.joint_normal = jn, .use_coplanar = false, .use_colinear = false}));
    print("non-penetration + co-planar/linear", run(*m, start, {.joint_normal = jn}));
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
    print("truth (the check's floor)", run(*m, m->truth, {.max_iterations = 0}));
    int good = 0;
    double worst_rot = 0.0, worst_trans = 0.0, worst_pen = 0.0;
    for (int s = 1; s <= seeds; ++s) {
        const Outcome o = run(*m, perturbed_truth(*m, angle_deg, shift_m, unsigned(s)),
                              {.joint_normal = joint_normal(), .free_iterations = free_iterations});
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

// Per free block: the rotation (deg) and the translation of its centroid (mm) of step u.
void print_step(const char* label, const MonumentAssembly& m,
                const ra::assembly_detail::Prepared& p, const ra::assembly_detail::Frames& f,
                const Eigen::VectorXd& u) {
    std::printf("%-28s", label);
    for (std::size_t b = 0; b < m.problem.blocks.size(); ++b) {
        const int s = p.slot[b];
        if (s < 0) continue;
        std::printf("  %s %.4f deg %.3f mm", m.problem.blocks[b].id.c_str(),
                    180.0 / M_PI * u.segment<3>(6 * s).norm() / f.length_m[b],
                    1e3 * u.segment<3>(6 * s + 3).norm());
    }
    std::printf("\n");
}

void print_rows(const char* term, const std::vector<ra::assembly_detail::Row>& rows,
                std::size_t links) {
    for (std::size_t l = 0; l < links; ++l) {
        double sum = 0.0, sq = 0.0;
        int n = 0;
        for (const auto& r : rows)
            if (std::size_t(r.link) == l) sum += r.rhs, sq += r.rhs * r.rhs, ++n;
        if (n > 0)
            std::printf("%s link %zu: %d rows, residual mean %.3f rms %.3f mm\n", term, l, n,
                        1e3 * sum / n, 1e3 * std::sqrt(sq / n));
    }
}

int terms(int n, const std::string& section, std::uint64_t seed, double step_m) {
    namespace ad = ra::assembly_detail;
    std::vector<std::string> ids{"c0b0", "c0b1", "c1b0"};
    if (n >= 4) ids.push_back("c1b1");
    auto m = monument_assembly(section, seed, ids, step_m);
    if (!m) return std::fprintf(stderr, "%s\n", m.error().message.c_str()), 1;
    const ra::AssemblyConfig c{.joint_normal = joint_normal()};
    const ad::Prepared prep = ad::prepare(m->problem, c);
    const ad::Rows rows = ad::build_rows(m->problem, prep, m->truth, c);
    const ad::Frames frames = ad::frames_of(m->problem, m->truth);
    for (std::size_t l = 0; l < m->problem.contacts.size(); ++l)
        std::printf("contact link %zu: %s\n", l,
                    ra::link_name(m->problem, m->problem.contacts[l]).c_str());
    for (std::size_t l = 0; l < m->problem.coplanar.size(); ++l)
        std::printf("co-planar link %zu: %s\n", l,
                    ra::link_name(m->problem, m->problem.coplanar[l]).c_str());
    print_rows("contact", rows.contact, m->problem.contacts.size());
    print_rows("co-planar", rows.coplanar, m->problem.coplanar.size());
    print_rows("co-linear", rows.colinear, m->problem.colinear.size());
    const ad::IterationQp q = ad::iteration_qp(rows, prep, frames, true);
    auto solve = [&](const Eigen::MatrixXd& H, const Eigen::VectorXd& g, bool constrained) {
        const Eigen::MatrixXd C = constrained ? q.C : Eigen::MatrixXd(0, H.cols());
        const Eigen::VectorXd d = constrained ? q.d : Eigen::VectorXd(0);
        return ra::solve_constrained_normal(H, g, C, d).u;
    };
    std::printf("first step from the truth (u per block):\n");
    print_step("all, unconstrained", *m, prep, frames, solve(q.H(), q.g(), false));
    print_step("all, constrained", *m, prep, frames, solve(q.H(), q.g(), true));
    print_step("without F_reg", *m, prep, frames, solve(q.H_cp + q.H_cl, q.g_cp + q.g_cl, true));
    print_step("without F_cp", *m, prep, frames, solve(q.H_reg + q.H_cl, q.g_reg + q.g_cl, true));
    print_step("without F_cl", *m, prep, frames, solve(q.H_reg + q.H_cp, q.g_reg + q.g_cp, true));
    std::printf("gradient norms |g|: F_reg %.3g  F_cp %.3g  F_cl %.3g\n", q.g_reg.norm(),
                q.g_cp.norm(), q.g_cl.norm());
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
    if (mode == "terms" && argc > 2)
        return terms(std::atoi(argv[2]), argc > 3 ? argv[3] : "octagon-wall",
                     argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 0,
                     argc > 5 ? std::atof(argv[5]) * 1e-3 : 0.005);
    std::fprintf(
        stderr,
        "usage: %s fig15 [SECTION] [SEED] [STEP_MM] | wall N SEEDS [SECTION] [SEED] [STEP_MM]\n",
        argv[0]);
    return 2;
}
