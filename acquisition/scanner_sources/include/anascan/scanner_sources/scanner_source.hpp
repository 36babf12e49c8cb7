#pragma once
/// \file
/// Where a capture session gets its scanner: a device URI opened through the device
/// registry (real backends and the simulated `sim:` scanners), and the simulated operator
/// that walks a simulated scanner around the block. The field app and `anascan capture`
/// both use these, so neither needs to know a backend.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "anascan/acquisition/capture/capture_session.hpp"

namespace anascan::scanner_sources {

using acquisition::CaptureRequest;
using acquisition::ScannerOpener;

/// Device settings asked for at every opening; absent fields are left as they are.
struct ScannerSettings {
    std::optional<double> exposure_us;       ///< Microseconds.
    std::optional<double> angular_step_deg;  ///< Terrestrial scanners, degrees.
    std::optional<double> max_range_m;       ///< Farthest depth kept, metres.
};

struct ScannerSource {
    std::string uri;  ///< `sim:structured-light/small-block`, `v4l2:/dev/video2`, ...
    ScannerSettings settings;
    /// Fault injection (simulated scanners only): unplugged during the capture after this
    /// many, on the first opening only (the device "plugged in again" works); -1: never.
    int sim_unplug_after = -1;
};

/// Opens the source's device as a scanner (kUnsupported naming it when it is a camera),
/// applying the settings (kInvalidArgument naming the setting and its range).
ScannerOpener make_scanner_opener(ScannerSource source);

/// One device a session could capture from.
struct ScannerListing {
    std::string uri;
    std::string model;
    bool simulated = false;
};

/// Scanners present now (simulated ones always).
std::vector<ScannerListing> list_scanners();

/// True for `sim:` URIs.
bool is_simulated(const std::string& uri);

/// The simulated operator: a walk around the block, the stone turned over half way; on a
/// circle around its centre, or along its footprint (sim/scanning_tour.hpp).
struct SimulatedTour {
    int views = 24;
    int flip_after = 12;  ///< 0: never turned over.
    double distance_m = 1.1;
    std::uint64_t seed = 1;
    bool follow_footprint = false;
};

/// Views per side of the footprint walk the tour would take around the stone a simulated
/// device (`sim:...`) looks at: as many as the block's outline needs for its distance.
Expected<int> footprint_views_per_side(const std::string& uri, const SimulatedTour& tour);

/// The request of view `index` (0-based) of the tour: a simulated scanner is moved to the
/// view (and the stone turned over when the tour says) right before the capture, and the
/// scan's true pose is recorded; a real scanner captures where the operator put it.
CaptureRequest tour_request(const SimulatedTour& tour, int index);

/// Whether the stone is turned over right before view `index`.
bool tour_turns_over_before(const SimulatedTour& tour, int index);

/// A view planned by the next-best-view, in the session's truth frame (the frame of the
/// stone's first placement, which moves with the stone).
struct GuidedView {
    Eigen::Vector3d sensor_m = Eigen::Vector3d::Zero();
    Eigen::Vector3d aim_m = Eigen::Vector3d::Zero();
    bool turned = false;  ///< The stone lies turned over.
};

/// The request of a guided view: a simulated scanner stands where the view says; the true
/// pose is recorded as for the tour.
CaptureRequest guided_request(const SimulatedTour& tour, const GuidedView& view);

/// The request of view `index` of the turned side's fixed walk (`views` views around), for
/// the guided operator right after turning the stone over; the first is marked as the turn.
CaptureRequest turned_side_request(const SimulatedTour& tour, int index, int views);

}  // namespace anascan::scanner_sources
