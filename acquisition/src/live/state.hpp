#pragma once
// Internal state and steps of LiveRegistrar (live_registration*.cpp).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "anascan/acquisition/live/device_scale.hpp"
#include "anascan/acquisition/live/live_registration.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "live/votes.hpp"

namespace anascan::acquisition {
namespace live {

/// The reduced copy of one scan and what the session knows of it.
struct ScanEntry {
    std::int64_t seq = 0;
    PointCloud cloud;  ///< Stone only, down-sampled, unit normals toward the sensor.
    Eigen::Vector3d sensor_origin_m = Eigen::Vector3d::Zero();  ///< Scan frame.
    Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();       ///< Scan frame.
    double radius_m = 0.0;                 ///< Of the bounding sphere around the centroid.
    std::optional<ScanFeatures> features;  ///< Computed on demand, kept.
    int side = 0;  ///< Turn-overs the operator marked before this scan (which side is up).
    std::shared_ptr<const KdTree> tree;  ///< Over cloud.positions, built on first use.
    bool registered = false;
    bool excluded = false;
    /// Taken out by the group consistency check (why); out of the model like an excluded scan.
    std::string flagged;
    int group = -1;
    Pose T_group_scan = Pose::Identity();
};

/// Registered, not excluded, not flagged: part of its group's model.
inline bool active(const ScanEntry& e) { return e.registered && !e.excluded && e.flagged.empty(); }

/// A group's members and their poses when its consistency was last checked.
struct CheckedGroup {
    std::vector<std::size_t> scans;
    std::vector<Pose> poses;
};

/// The entries a merge moved into a group (the group merged in, whole), kept until the group
/// next passes its consistency check: a check that fails after a merge is evidence against
/// the merge, so the part leaves whole (see consistency.cpp).
struct MergedPart {
    int from = -1;                   ///< The group merged in.
    std::vector<std::size_t> scans;  ///< Its entries (indices into State::scans).
    /// Entries add() placed in the group after this merge: their placement rests on it.
    std::vector<std::size_t> followers;
};

/// What a failed check decided for each scan of a group (by position in the group's list).
struct Verdicts {
    std::vector<std::string> reasons;        ///< Why it is taken out and flagged; empty: kept.
    std::vector<std::string> disagreements;  ///< The failed pair test of each reason.
    /// 0: stays in the group; m + 1: leaves with merged part m as a group of its own.
    std::vector<int> unit;
    std::vector<std::string> moved;  ///< Why it leaves with its part (unit > 0).
};

/// A multi-view link between two entries (indices into State::scans).
struct Link {
    std::size_t target = 0, source = 0;
    std::vector<FineCorrespondence> correspondences;
};

/// Outcome of one verified (or not) fine registration.
struct Verified {
    FineRegistrationResult fine;
    std::string rejection;  ///< Empty when verified.
};

/// The reduced copy of a new scan, or why it cannot be used.
struct Prepared {
    ScanEntry entry;
    std::string problem;
};

/// Reduces a scan (see LiveRegistrationConfig): the stone-only down-sampled cloud.
Prepared prepare_scan(LiveScanInput input, const LiveRegistrationConfig& config);

/// How a scan is placed: the newest scan (the operator's priors are about it) or one placed
/// again; right after the operator marked a turn-over.
struct PlaceMode {
    bool newest = true;
    bool turned = false;
};

/// The merged model a hypothesis was last verified against, with its k-d tree.
struct ModelCache {
    int group = -1;
    std::vector<std::size_t> scans;  ///< Entries merged, in order.
    std::vector<Pose> poses;         ///< Their poses when merged.
    PointCloud cloud;                ///< Group frame.
    std::unique_ptr<KdTree> tree;    ///< Over cloud.positions.
};

/// The session's current verification bounds (see LiveRegistrationConfig).
struct VerificationLimits {
    double max_rms_m = 0.0;
    double max_normal_deviation_deg = 0.0;
};

/// Why a fine registration is not acceptable (batch registration's verification); empty
/// when it is.
std::string rejection(const FineRegistrationResult& fine, const LiveRegistrationConfig& config,
                      const VerificationLimits& limits);

/// How far a prediction's refined pose may be from it.
enum class CorrectionCheck {
    kNone,        ///< Not a prediction (a global pose): no bound.
    kBound,       ///< LiveRegistrationConfig::max_prior_correction_* (group merges).
    kBoundOrFit,  ///< Also larger ones that fit like the session (max_fitting_correction_*).
};

/// A predicted pose and the hypothesis that predicted it.
using Prior = std::pair<LiveHypothesis, Pose>;

/// The operator's predicted poses from the poses of the scans next to it in the capture order
/// (`recent[0]` the nearest, at most 3 used): constant velocity ("motion-prior"), double step
/// ("motion-prior-2", elevations alternating), "previous-pose". Time-symmetric: scans after
/// it, nearest first, predict it backwards.
std::vector<Prior> motion_priors(const std::vector<Pose>& recent);

/// Mean of a cloud's points (its frame; zero when empty).
Eigen::Vector3d cloud_centroid(const PointCloud& cloud);

}  // namespace live

struct LiveRegistrar::State {
    LiveRegistrationConfig config;
    /// Measured on the first usable scan; `config`'s lengths follow it (lengths_for_device).
    std::optional<DeviceScale> device_scale;
    std::vector<live::ScanEntry> scans;  ///< In add order (usable scans only).
    std::map<std::int64_t, std::size_t> index_of_seq;
    std::vector<live::Link> links;
    std::optional<InvariantRadii> radii_m;  ///< Fixed at the first features.
    std::optional<SaliencyLevels> levels;   ///< Fixed at the first features.
    int next_group = 0;
    bool awaiting_turn = false;  ///< Turned over: no cheap hypothesis until one is placed.
    std::set<std::pair<std::size_t, std::size_t>> merge_tried;  ///< Global pairs tried (a, b).
    /// Link pairs tried (t, s) and the relative pose T_t_s they were tried from: tried again
    /// when the poses moved (see LiveRegistrationConfig::link_retry_m).
    std::map<std::pair<std::size_t, std::size_t>, Pose> link_tried;
    LiveRefineReport report;
    std::function<bool()> interrupt;  ///< Set during refine(); see LiveRegistrar::refine.
    /// True (and noted in the report) when refine() should stop: a new scan is waiting.
    bool interrupted() {
        if (!report.interrupted && interrupt && interrupt()) report.interrupted = true;
        return report.interrupted;
    }
    std::vector<double> link_rms_m;      ///< RMS of every multi-view link (the session's noise).
    std::vector<double> accepted_rms_m;  ///< Of every accepted add() decision.
    std::vector<double> accepted_normal_deviation;  ///< Degrees, same.
    /// On the first usable scan: measures the device's scale and raises config's lengths to
    /// it; a note for the decision's message (empty when nothing was measured).
    std::string adopt_device_scale(const PointCloud& cloud);
    /// Prepares and places a scan (add: `newest`; reregister: not, so no operator priors).
    LiveDecision place(LiveScanInput scan, bool newest, std::optional<int> side = std::nullopt);
    /// The cheap hypotheses, then global registration, for the new entry `index`; sets
    /// `group` and the decision's method and attempts. None: it opens a new group.
    std::optional<live::Verified> hypothesise(std::size_t index, live::PlaceMode mode, int& group,
                                              LiveDecision& decision);
    /// Marks entry `index` registered, in `group` with the accepted pose, or in a new group.
    void record(std::size_t index, const std::optional<live::Verified>& accepted, int group,
                bool first, LiveDecision& decision);
    /// Verification bounds from the config and the session's accepted figures.
    live::VerificationLimits limits() const;
    /// Largest RMS a global hypothesis may have to count (see global_rms_median_factor).
    double rms_gate() const;
    /// The motion prior that verified last.
    mutable LiveHypothesis last_prior = LiveHypothesis::kMotionPrior;
    /// Votes for the transform between two groups (lower id first), across refine() calls.
    std::map<std::pair<int, int>, live::PoseVotes> merge_votes;

    /// Registered, not excluded entries of `group`, most recent first.
    std::vector<std::size_t> members(int group) const;
    /// Groups with a registered, not excluded scan, ascending.
    std::vector<int> groups() const;
    /// Every group's members (as members()), in one pass over the scans: the merge loops
    /// visit every pair of groups, and a pass per pair cost minutes on long sessions.
    std::map<int, std::vector<std::size_t>> group_members() const;
    /// Features of entry i (computed at the session's radii and levels on first use).
    const ScanFeatures& features(std::size_t i);

    mutable live::ModelCache model_cache;
    /// The merged model of `candidates` (group frame), cached while they and their poses stay.
    const live::ModelCache& model_of(int group, const std::vector<std::size_t>& candidates) const;
    /// Fine registration of `entry` from `T_group_scan` against the group's model. For a
    /// prediction (`check` not kNone) the refined pose is also rejected when it moved too
    /// far from it, checked before the slide probes (a wrong basin is not worth probing)
    /// and after them.
    live::Verified verify_hypothesis(
        const live::ScanEntry& entry, int group, const Pose& T_group_scan,
        live::CorrectionCheck check = live::CorrectionCheck::kNone) const;
    /// Why a pose refined from the prediction `T_prior` cannot come from it (moved too far,
    /// so the fine registration fell into another minimum); empty when it can.
    std::string correction_problem(const live::ScanEntry& entry, const Pose& T_prior,
                                   const FineRegistrationResult& fine,
                                   live::CorrectionCheck check) const;
    /// Restarts along the weakest direction of `v` (see LiveRegistrationConfig::slide_probe_m).
    void probe_slides(const live::ScanEntry& entry, const PointCloud& model, const KdTree& tree,
                      live::Verified& v) const;
    /// The cheap hypotheses (motion prior, previous pose), in order; appends attempts.
    std::optional<live::Verified> try_cheap(const live::ScanEntry& entry, int& group,
                                            LiveMethod& method, LiveDecision& decision) const;
    /// The operator's predicted poses of a new scan (motion priors, previous pose) in the
    /// group of the latest registered scan (set in `group`); none after a turn-over.
    std::vector<live::Prior> priors(std::int64_t seq, int& group) const;
    /// Registered scans tried by global registration for entry `entry_index`, most recent
    /// first (at most LiveGlobalConfig::max_targets).
    std::vector<std::size_t> global_targets(std::size_t entry_index) const;
    /// Adds the verified hypotheses of `g` (entry against `target`) within the RMS gate to
    /// `box`; returns the one of largest overlap near one of `near_priors`, if any.
    const HypothesisOutcome* vote(const GlobalRegistrationResult& g, std::size_t target,
                                  const live::ScanEntry& entry,
                                  const std::vector<live::Prior>& near_priors,
                                  live::PoseVotes& box) const;
    /// A globally registered pose: a verified pose near a prior, else one that several
    /// target scans vote for (or the only target's success).
    std::optional<Pose> global_pose(std::size_t entry_index, int& group, LiveDecision& decision);
    /// Global registration against registered scans of every group, most recent first.
    std::optional<live::Verified> try_global(std::size_t entry_index, int& group,
                                             LiveDecision& decision);

    /// Group consistency (consistency.cpp): each group whose scans or poses changed since its
    /// last check is checked; the scans to take out are flagged and leave the group, and what
    /// stays is split into the parts that overlapping, agreeing pairs hold together (new
    /// groups: their updates are returned).
    std::vector<PoseUpdate> check_groups();
    void check_group(int group, std::vector<PoseUpdate>& regrouped);
    /// The merged parts of `group` (oldest first) that a disagreeing pair of `result` touches:
    /// a part whose own scans disagree is flagged whole, one that only disagrees with the
    /// rest leaves as a group of its own, and so does every part merged after (onto a model
    /// that held it).
    void take_out_merged_parts(int group, const std::vector<std::size_t>& ids,
                               const GroupConsistency& result,
                               const std::vector<std::string>& names, live::Verdicts& verdicts);
    /// The kept scans of `group` by components of agreeing pairs of `result` within each unit
    /// (the group's own scans, each part that leaves): the component of the earliest of the
    /// group's own stays, each other one becomes a group of its own, in the frame of its first
    /// scan (consistency_split.cpp).
    void split_unsupported(int group, const std::vector<std::size_t>& ids,
                           const GroupConsistency& result, const live::Verdicts& verdicts,
                           std::vector<PoseUpdate>& regrouped);
    std::map<int, live::CheckedGroup> checked_groups;
    /// Merges into each group since it last passed its check, oldest first.
    std::map<int, std::vector<live::MergedPart>> unchecked_merges;

    /// Multi-view refinement machinery (live_registration_refine.cpp).
    std::size_t make_links();
    /// The k-d tree over entry i's cloud (built on first use, kept).
    const KdTree& tree_of(std::size_t i);
    /// Fine registers the link t <- s from the relative pose `initial`; true when it was added.
    bool try_link(std::size_t t, std::size_t s, const Pose& initial);
    /// Forecast overlap of the pair (t, s) at `initial`, kept until their poses move.
    double forecast(std::size_t t, std::size_t s, const Pose& initial);
    /// The earlier scans of entry s's group it is predicted to overlap most (at most
    /// LiveLinkConfig::max_per_scan per side, best first); drops s's links to the others.
    std::vector<std::size_t> link_partners(std::size_t s);
    /// Forecasts by pair (t, s) and the relative pose each was computed at (-1: none yet).
    struct LinkForecast {
        Pose at = Pose::Identity();
        double fraction = -1.0;
    };
    std::map<std::pair<std::size_t, std::size_t>, LinkForecast> link_forecasts;
    std::vector<PoseUpdate> refine_groups();
    /// Multi-view refinement of group g's poses; appends the changed ones.
    void refine_group(int g, std::vector<PoseUpdate>& updates);
    std::vector<PoseUpdate> merge_groups();
    /// Votes for the transform between groups a and b from global registrations of their
    /// scan pairs not tried yet. The merge's updates once the votes decide; empty updates
    /// when the call's `attempts` budget ran out; none when the pairs are exhausted.
    std::optional<std::vector<PoseUpdate>> merge_by_votes(int a, int b,
                                                          const std::vector<std::size_t>& in_a,
                                                          const std::vector<std::size_t>& in_b,
                                                          std::size_t& attempts);
    /// Global registration of entry j against entry i, verified poses (group a <- group b)
    /// within the RMS gate added to `box`.
    void vote_scan_pair(std::size_t i, std::size_t j, live::PoseVotes& box);
    /// Group merges by global registration of the whole groups' clouds under the up
    /// constraint (live_registration_merge.cpp).
    std::vector<PoseUpdate> merge_whole_groups();
    /// The pose to merge two groups on from their whole-group registration: the verified
    /// hypothesis of least RMS, within the groups' RMS gate, fitting clearly better than
    /// every other verified pose (distinct at the source group's centroid); else none.
    std::optional<Pose> clear_whole_group_match(const GlobalRegistrationResult& g,
                                                const Eigen::Vector3d& source_centroid_m) const;
    /// Mean viewing direction of a group's scans (its frame): the stone's up; none for a
    /// group of too few scans or of views that do not agree on a side.
    std::optional<Eigen::Vector3d> group_up(int group) const;
    int group_side(int group) const;  ///< Side of its most recent scan.
    /// Up kept (same side) or turned down (after a turn-over) between two groups, if known.
    std::optional<AxisConstraint> up_constraint(int target, int source) const;
    int turn_count = 0;  ///< Turn-overs marked so far.
    /// Group merges by the capture order (live_registration_sequence_merge.cpp): a scan whose
    /// neighbour in the order lies in another group of the same side is predicted there by
    /// the motion priors (run backwards when the neighbour comes after it) and verified.
    std::vector<PoseUpdate> merge_by_sequence();
    /// The sequence merge of entry i with its neighbour in `direction`: none when it does not
    /// apply (or was tried at this size), else the merge's updates (empty: it did not verify).
    std::optional<std::vector<PoseUpdate>> sequence_merge(std::size_t i, int direction);
    /// The operator's predicted poses of entry `i` in group `group` from the entries next to
    /// it in the capture order (`direction` +1: those after it, run backwards; -1: before).
    std::vector<live::Prior> sequence_priors(std::size_t i, int group, int direction) const;
    /// Sequence merges tried: (entry, direction) and the other group's scans then.
    std::map<std::pair<std::size_t, int>, std::size_t> sequence_merge_tried;
    /// Group pairs tried whole and the smaller and larger group's scans then. A group is
    /// known by its first scan (lower first), not its id: a part that a check takes out of a
    /// wrong merge comes back under a new id, and keyed by id the same merge was tried again
    /// at once, again and again (random-block:1, guided: 354 splits in 24 scans).
    std::map<std::pair<std::size_t, std::size_t>, std::pair<std::size_t, std::size_t>>
        whole_merge_tried;
    /// The group's stone-only clouds in its frame, merged and voxel down-sampled.
    PointCloud group_cloud(int group) const;
    /// The voted transform between two groups refined by fine registration of the groups'
    /// clouds (unchanged when that does not verify or leaves the votes' tolerance).
    Pose refined_merge(int into, int from, const Pose& T_into_from) const;
    /// Moves every scan of group `from` into `into` (T_into_from); returns the updates.
    std::vector<PoseUpdate> merge(int into, int from, const Pose& T_into_from);
};

}  // namespace anascan::acquisition
