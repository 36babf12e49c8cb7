#include "anascan/processing/reassembly/assembly_probe.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>

#include "assembly_steps.hpp"

namespace anascan::reassembly {
namespace {

using namespace assembly_detail;

// The links of `rows` that have no row: their faces do not meet.
std::vector<std::string> untouched(const AssemblyProblem& p, const std::vector<Row>& rows) {
    std::set<int> touching;
    for (const Row& r : rows) touching.insert(r.link);
    std::vector<std::string> out;
    for (std::size_t l = 0; l < p.contacts.size(); ++l)
        if (!touching.count(int(l))) out.push_back(link_name(p, p.contacts[l]));
    return out;
}

// Per free block, the unit translation least curved in its own 3x3 part of the normal
// matrix of the three terms at poses T.
std::vector<Eigen::Vector3d> weakest_translations(const AssemblyProblem& p, const Prepared& prep,
                                                  const Rows& rows, const std::vector<Pose>& T) {
    const Frames frames = frames_of(p, T);
    const Eigen::MatrixXd H = iteration_qp(rows, prep, frames, false).H();
    std::vector<Eigen::Vector3d> out(p.blocks.size(), Eigen::Vector3d::Zero());
    for (std::size_t b = 0; b < p.blocks.size(); ++b) {
        const int s = prep.slot[b];
        if (s < 0) continue;
        const Eigen::Matrix3d Ht = H.block<3, 3>(6 * s + 3, 6 * s + 3);
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(Ht);
        out[b] = eig.eigenvectors().col(0).normalized();  // Eigenvalues ascend.
    }
    return out;
}

bool fits_as_well(const TermResiduals& probe, const TermResiduals& base,
                  const DeterminacyConfig& c) {
    auto within = [&](double a, double b) { return a <= c.rms_ratio * b + c.rms_floor_m; };
    return within(probe.registration_rms_m, base.registration_rms_m) &&
           within(probe.coplanar_rms_m, base.coplanar_rms_m) &&
           within(probe.colinear_rms_m, base.colinear_rms_m);
}

void name_untouched(const std::vector<std::string>& pairs, AssemblyResult& r) {
    for (const std::string& pair : pairs) r.offending.push_back("pair " + pair + " does not touch");
}

}  // namespace

Expected<Determinacy> probe_determinacy(const AssemblyProblem& p, const AssemblyResult& assembled,
                                        const AssemblyConfig& config,
                                        const DeterminacyConfig& probe) {
    if (auto ok = validate_problem(p, config); !ok) return Unexpected(ok.error());
    const std::vector<Pose>& T = assembled.T_world_block;
    const Prepared prep = prepare(p, config);
    const Rows rows = build_rows(p, prep, T, config);
    Determinacy out{.untouched_pairs = untouched(p, rows.contact)};
    if (assembled.history.empty()) return out;
    const TermResiduals& base = assembled.history.back();
    const std::vector<Eigen::Vector3d> weak = weakest_translations(p, prep, rows, T);
    for (std::size_t b = 0; b < p.blocks.size(); ++b) {
        if (prep.slot[b] < 0) continue;
        for (double sign : {1.0, -1.0}) {
            std::vector<Pose> start = T;
            const Eigen::Vector3d shift = sign * probe.start_m * weak[b];
            start[b] = Eigen::Translation3d(shift) * T[b];
            auto r = assemble_blocks(p, start, config);
            ++out.restarts;
            if (!r) return Unexpected(r.error());
            if (r->status != AssemblyStatus::kOk || r->history.empty()) continue;
            const double moved = (r->T_world_block[b].translation() - T[b].translation()).norm();
            if (moved > probe.moved_m && fits_as_well(r->history.back(), base, probe)) {
                out.loose.push_back({.block = int(b),
                                     .direction = weak[b],
                                     .start_m = sign * probe.start_m,
                                     .moved_m = moved});
                break;
            }
        }
    }
    return out;
}

Expected<NonConvergence> diagnose_not_converged(const AssemblyProblem& p,
                                                const AssemblyResult& assembled,
                                                const AssemblyConfig& config,
                                                double max_angle_deg) {
    if (auto ok = validate_problem(p, config); !ok) return Unexpected(ok.error());
    const std::vector<Pose>& T = assembled.T_world_block;
    const Prepared prep = prepare(p, config);
    const Rows rows = build_rows(p, prep, T, config);
    NonConvergence out{.untouched_pairs = untouched(p, rows.contact)};
    AssemblyConfig one = config;
    one.max_iterations = 1;
    one.free_iterations = 0;
    auto next = assemble_blocks(p, T, one);
    if (!next) return Unexpected(next.error());
    const Frames frames = frames_of(p, T);
    const std::vector<Eigen::Vector3d> weak = weakest_translations(p, prep, rows, T);
    int most = -1;
    Eigen::Vector3d motion = Eigen::Vector3d::Zero();
    for (std::size_t b = 0; b < p.blocks.size(); ++b) {
        if (prep.slot[b] < 0) continue;
        const Pose D = next->T_world_block[b] * T[b].inverse();
        const Eigen::Vector3d m = D * frames.reference_m[b] - frames.reference_m[b];
        if (most < 0 || m.norm() > motion.norm()) most = int(b), motion = m;
    }
    const double cos_max = std::cos(max_angle_deg * std::numbers::pi / 180.0);
    if (most >= 0 && motion.norm() > 0.0 &&
        std::abs(motion.normalized().dot(weak[std::size_t(most)])) >= cos_max) {
        out.drifting.push_back({.block = most,
                                .direction = motion.normalized(),
                                .start_m = 0.0,
                                .moved_m = motion.norm()});
    }
    return out;
}

void name_non_convergence(const AssemblyProblem& p, const NonConvergence& d, AssemblyResult& r) {
    if (!d.explained()) return;
    name_untouched(d.untouched_pairs, r);
    for (const LooseBlock& l : d.drifting) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "%s still moves %.3f mm per iteration along (%.2f %.2f %.2f), the "
                      "direction its pairs hold least",
                      p.blocks[std::size_t(l.block)].id.c_str(), 1e3 * l.moved_m, l.direction.x(),
                      l.direction.y(), l.direction.z());
        r.offending.push_back(text);
    }
    r.message +=
        "; the pairs may not fix every block: add a pair or a co-planar face that "
        "holds it";
}

void mark_underdetermined(const AssemblyProblem& p, const Determinacy& d, AssemblyResult& r) {
    if (d.fixed()) return;
    r.status = AssemblyStatus::kUnderdetermined;
    name_untouched(d.untouched_pairs, r);
    for (const LooseBlock& l : d.loose) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "%s slides along (%.2f %.2f %.2f): restarted %.0f mm along it, it ended "
                      "%.1f mm away, fitting as well",
                      p.blocks[std::size_t(l.block)].id.c_str(), l.direction.x(), l.direction.y(),
                      l.direction.z(), 1e3 * std::abs(l.start_m), 1e3 * l.moved_m);
        r.offending.push_back(text);
    }
    r.message = "the pairs do not fix every block: add a pair or a co-planar face that holds it";
}

}  // namespace anascan::reassembly
