#pragma once
// The simulated operator of `anascan capture --tour guided`: after each scan it asks the
// next-best-view where to stand, walks there (converting the plan from the model's frame to
// the stone as it lies, as an operator reads a hint against the stone in front of them),
// turns the stone over when the plan says so, and stops at the target coverage.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "anascan/acquisition/capture/capture_session.hpp"
#include "anascan/scanner_sources/scanner_source.hpp"

namespace anascan::cli {

class GuidedOperator {
public:
    GuidedOperator(scanner_sources::SimulatedTour tour, double target_fraction)
        : tour_(tour), target_fraction_(target_fraction) {}

    /// The request of view `index` (0-based), or nothing when the tour is over: the target
    /// coverage is reached, or no view on either side adds anything. Waits for the session
    /// to register the scans before (the plan needs their poses).
    std::optional<acquisition::CaptureRequest> next(acquisition::CaptureSession& session,
                                                    int index);

    /// Each plan's own time (not the coverage before it), seconds.
    const std::vector<double>& plan_times_s() const { return plan_times_s_; }

private:
    /// A view the plan asked for: where, in the frame of which group, and the scan it gave.
    struct AskedView {
        Eigen::Vector3d sensor_model_m;
        int group = -1;
        std::int64_t seq = 0;
    };

    std::optional<acquisition::CaptureRequest> after_turn();
    /// Records the last asked view as failed when its scan is not in the model.
    void note_whether_the_asked_view_joined(const std::vector<acquisition::ScanRecord>& scans);
    /// The failed views in the frame of the model as it is now.
    std::vector<Eigen::Vector3d> failed_views(
        const std::vector<acquisition::ScanRecord>& scans) const;

    scanner_sources::SimulatedTour tour_;
    double target_fraction_;
    bool turned_ = false;
    std::int64_t last_before_turn_ = 0;  ///< Scans in the session when it was turned over.
    int turned_side_views_ = 0;  ///< Fixed views taken since the turn (until the sides join).
    std::vector<double> plan_times_s_;
    std::optional<AskedView> asked_;
    std::vector<AskedView> failed_;  ///< Asked views whose scans did not join the model.
};

}  // namespace anascan::cli
