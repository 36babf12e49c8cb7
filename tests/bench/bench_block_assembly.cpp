// The block assembly: one iteration with 4 blocks and about 50k constraint samples, its QP
// solved by ours (least distance programming, Lawson-Hanson NNLS on Eigen) and by Debian's
// Clp (quadratic primal simplex) on the same problem; and a 12-block assembly whole-process
// (features of the 12 models, Horn placement skipped: a start 2° and 15 mm off the truth,
// iterations to convergence). Blocks are analytic boxes in a row with co-planar façades
// and tops (tests/processing/reassembly/box_mesh.hpp).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <random>

#include "../processing/reassembly/box_mesh.hpp"
#include "anascan/processing/reassembly/assembly_probe.hpp"
#include "anascan/processing/reassembly/block_assembly.hpp"
#include "anascan/processing/reassembly/constrained_lsq.hpp"
#include "reassembly/assembly_steps.hpp"
#if ANASCAN_HAVE_CLP
#include "../processing/reassembly/clp_qp.hpp"
#endif

namespace {

using namespace anascan;
namespace ra = anascan::reassembly;

struct Wall {
    std::vector<Mesh> meshes;
    ra::AssemblyProblem problem;
    std::vector<Pose> start;
};

int face_along(const ra::AssemblyBlock& b, const Eigen::Vector3d& n) {
    for (const ra::PlanarFace& f : b.features.faces)
        if (f.normal.dot(n) > 0.99) return f.id;
    return -1;
}

// n boxes of 0.8-1.2 m in a row on a `step_m` grid, in the wall frame, started off.
Wall row_wall(int n, double step_m, bool features) {
    Wall w;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> len(0.8, 1.2);
    std::normal_distribution<double> N(0.0, 1.0);
    double x = 0.0;
    for (int i = 0; i < n; ++i) {
        const double l = len(rng);
        Mesh m = ra::testing::box_mesh({l, 0.6, 0.5}, step_m);
        for (auto& p : m.vertices.positions) p.x() += float(x + 0.5 * l);
        w.meshes.push_back(std::move(m));
        x += l;
        const Eigen::Vector3d axis = Eigen::Vector3d(N(rng), N(rng), N(rng)).normalized();
        w.start.push_back(i == 0
                              ? Pose::Identity()
                              : Pose(Eigen::Translation3d(0.015 * axis) *
                                     Eigen::AngleAxisd(2.0 * M_PI / 180.0, axis.unitOrthogonal())));
    }
    if (!features) return w;
    for (int i = 0; i < n; ++i)
        w.problem.blocks.push_back(ra::assembly_block("b" + std::to_string(i), w.meshes[i]));
    for (int i = 0; i + 1 < n; ++i) {
        const auto& a = w.problem.blocks[std::size_t(i)];
        const auto& b = w.problem.blocks[std::size_t(i + 1)];
        w.problem.contacts.push_back({{i, face_along(a, Eigen::Vector3d::UnitX())},
                                      {i + 1, face_along(b, -Eigen::Vector3d::UnitX())}});
        for (const Eigen::Vector3d& n2 : {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1)})
            w.problem.coplanar.push_back({{i, face_along(a, n2)}, {i + 1, face_along(b, n2)}});
    }
    return w;
}

// The QP of the first iteration of 4 blocks with ~50k constraint samples.
struct Qp {
    Eigen::MatrixXd H, C;
    Eigen::VectorXd g, d;
};

const Qp& four_block_qp() {
    static const Qp qp = [] {
        const Wall w = row_wall(4, 0.004, true);
        ra::AssemblyConfig c;
        c.contact_samples_per_face = 8400;  // 3 joints x 2 sides x 8400 = 50k samples.
        const auto prep = ra::assembly_detail::prepare(w.problem, c);
        const auto rows = ra::assembly_detail::build_rows(w.problem, prep, w.start, c);
        ra::assembly_detail::Frames f;
        for (std::size_t b = 0; b < w.start.size(); ++b)
            f.reference_m.push_back(w.start[b] * Eigen::Vector3d(double(b), 0, 0)),
                f.length_m.push_back(0.4);
        const Eigen::MatrixXd A = ra::assembly_detail::row_matrix(rows.contact, prep, f, 1.0);
        Eigen::VectorXd b(Eigen::Index(rows.contact.size()));
        for (std::size_t i = 0; i < rows.contact.size(); ++i)
            b[Eigen::Index(i)] = rows.contact[i].rhs;
        return Qp{A.transpose() * A / double(A.rows()), A, A.transpose() * b / double(A.rows()), b};
    }();
    return qp;
}

void BM_AssemblyQp_Ours_4Blocks50k(benchmark::State& state) {
    const Qp& qp = four_block_qp();
    for (auto _ : state)
        benchmark::DoNotOptimize(ra::solve_constrained_normal(qp.H, qp.g, qp.C, qp.d).u);
    state.counters["constraints"] = double(qp.C.rows());
}
BENCHMARK(BM_AssemblyQp_Ours_4Blocks50k)->Unit(benchmark::kMillisecond);

#if ANASCAN_HAVE_CLP
void BM_AssemblyQp_Clp_4Blocks50k(benchmark::State& state) {
    const Qp& qp = four_block_qp();
    const Eigen::VectorXd ours = ra::solve_constrained_normal(qp.H, qp.g, qp.C, qp.d).u;
    Eigen::VectorXd u;
    for (auto _ : state) u = ra::testing::solve_qp_with_clp(qp.H, qp.g, qp.C, qp.d).u;
    state.counters["difference"] = (u - ours).norm() / std::max(1e-300, ours.norm());
}
BENCHMARK(BM_AssemblyQp_Clp_4Blocks50k)->Unit(benchmark::kMillisecond);
#endif

// One whole iteration (rows, QP, helical motion) of 4 blocks with ~50k samples.
void BM_AssemblyIteration_4Blocks50k(benchmark::State& state) {
    static const Wall w = row_wall(4, 0.004, true);
    ra::AssemblyConfig c;
    c.contact_samples_per_face = 8400;
    c.max_iterations = 1;
    for (auto _ : state) benchmark::DoNotOptimize(ra::assemble_blocks(w.problem, w.start, c));
}
BENCHMARK(BM_AssemblyIteration_4Blocks50k)->Unit(benchmark::kMillisecond);

// 12 blocks, whole process from the models: features, then the assembly to convergence.
void BM_Assembly_12Blocks_WholeProcess(benchmark::State& state) {
    const Wall meshes = row_wall(12, 0.005, false);
    for (auto _ : state) {
        Wall w = row_wall(12, 0.005, true);
        auto r = ra::assemble_blocks(w.problem, w.start, {});
        state.counters["iterations"] = r ? r->iterations : -1;
    }
}
BENCHMARK(BM_Assembly_12Blocks_WholeProcess)->Unit(benchmark::kSecond)->Iterations(1);

// What `blocks assemble` adds after an ok assembly of the 12 blocks: whether the pairs fix
// every block (a restart of each free block both ways along its weakest translation).
void BM_AssemblyProbe_12Blocks(benchmark::State& state) {
    const Wall w = row_wall(12, 0.005, true);
    auto r = ra::assemble_blocks(w.problem, w.start, {});
    if (!r || r->status != ra::AssemblyStatus::kOk) {
        state.SkipWithError("the 12-block assembly did not end ok");
        return;
    }
    for (auto _ : state) {
        auto d = ra::probe_determinacy(w.problem, *r, {});
        state.counters["restarts"] = d ? d->restarts : -1;
        state.counters["loose"] = d ? double(d->loose.size() + d->untouched_pairs.size()) : -1;
    }
}
BENCHMARK(BM_AssemblyProbe_12Blocks)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
