#pragma once
// The simulated operator of `anascan capture --tour guided`: after each scan it asks the
// next-best-view where to stand, walks there (converting the plan from the model's frame to
// the stone as it lies, as an operator reads a hint against the stone in front of them),
// turns the stone over when the plan says so, and stops at the target coverage.

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
    std::optional<acquisition::CaptureRequest> after_turn();

    scanner_sources::SimulatedTour tour_;
    double target_fraction_;
    bool turned_ = false;
    std::int64_t last_before_turn_ = 0;  ///< Scans in the session when it was turned over.
    int turned_side_views_ = 0;  ///< Fixed views taken since the turn (until the sides join).
    std::vector<double> plan_times_s_;
};

}  // namespace anascan::cli
