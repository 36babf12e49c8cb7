#pragma once
/// \file
/// Whether an assembly's pairs fix every block (docs/reassembly.md, "Is each block fixed?").
/// A flat joint carries almost nothing along itself: a block whose pairs leave it free to
/// slide ends wherever its start put it, and the constrained registration then reports `ok`
/// for a block metres off. Two tests, after an `ok` assembly:
/// - every matching face pair still touches: a pair with no sample on its partner face
///   exerts no force, so what the expert said about it was never used;
/// - each free block restarted a little along its weakest translation (the least curved
///   direction of its own part of the last iteration's normal matrix), both ways, with the
///   other blocks where they ended: if the assembly then converges elsewhere, fitting as
///   well, the pairs do not fix the block along that direction.
/// Pure geometry: no I/O, no logging, no threads; deterministic.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/reassembly/block_assembly.hpp"

namespace anascan::reassembly {

struct DeterminacyConfig {
    double start_m = 0.02;  ///< Restart this far along the weakest translation.
    /// A restart that converges further than this from the assembly's pose is elsewhere.
    double moved_m = 0.001;
    /// ... and fits as well when every term's RMS is within this ratio of the assembly's
    /// (plus the floor, for terms at the noise level).
    double rms_ratio = 1.1;
    double rms_floor_m = 1e-4;
};

/// A block the pairs leave free along `direction` (world frame, unit).
struct LooseBlock {
    int block = 0;
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();
    double start_m = 0.0;  ///< Signed start of the restart along the direction.
    double moved_m = 0.0;  ///< How far from the assembly's pose the restart converged.
};

struct Determinacy {
    std::vector<std::string> untouched_pairs;  ///< "A:2=B:5" with no sample on its partner.
    std::vector<LooseBlock> loose;
    int restarts = 0;  ///< Restarts run.
    bool fixed() const { return untouched_pairs.empty() && loose.empty(); }
};

/// The two tests above on the poses of an `ok` result (`assembled.T_world_block`).
Expected<Determinacy> probe_determinacy(const AssemblyProblem& problem,
                                        const AssemblyResult& assembled,
                                        const AssemblyConfig& config,
                                        const DeterminacyConfig& probe = {});

/// Marks `result` kUnderdetermined with what `d` found (no change when d.fixed()).
void mark_underdetermined(const AssemblyProblem& problem, const Determinacy& d,
                          AssemblyResult& result);

/// What the pairs say about an assembly that did not converge: the pairs that do not touch
/// at its end, and the block that one more step moves most when it moves along its least
/// fixed translation (within `max_angle_deg`; `moved_m` is that step's length, `start_m`
/// 0). No restarts: the end is not a minimum to restart from.
struct NonConvergence {
    std::vector<std::string> untouched_pairs;
    std::vector<LooseBlock> drifting;  ///< At most one block.
    bool explained() const { return !untouched_pairs.empty() || !drifting.empty(); }
};
Expected<NonConvergence> diagnose_not_converged(const AssemblyProblem& problem,
                                                const AssemblyResult& assembled,
                                                const AssemblyConfig& config,
                                                double max_angle_deg = 30.0);

/// Adds what `d` found to a kNotConverged `result`'s offending list and message (the status
/// stays: the probe cannot tell a slow convergence from a free block).
void name_non_convergence(const AssemblyProblem& problem, const NonConvergence& d,
                          AssemblyResult& result);

}  // namespace anascan::reassembly
