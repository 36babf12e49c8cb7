#include "anascan/sim/sim_tof_scanner.hpp"

#include <cstdio>

#include "anascan/sim/viewpoints.hpp"
#include "sim_capture_run.hpp"
#include "sim_scanner_parts.hpp"

namespace anascan::sim {
namespace {

drivers::Capabilities tof_capabilities() {
    drivers::Capabilities caps;
    caps.can_capture_scan = true;
    // 0.02 degrees keeps a full panorama under the simulator's 1e8 rays; the LMS-Z420i
    // goes finer, over smaller windows.
    caps.angular_step_deg = drivers::NumericRange{0.02, 5.0};
    caps.range_m = drivers::NumericRange{2.0, 800.0};
    caps.horizontal_field_deg = drivers::NumericRange{1.0, 360.0};  // the LMS-Z420i's sweep
    caps.vertical_field_deg = drivers::NumericRange{1.0, 80.0};
    return caps;
}

}  // namespace

std::unique_ptr<SimTofScanner> SimTofScanner::open(SimTofScannerConfig config) {
    return std::unique_ptr<SimTofScanner>(new SimTofScanner(std::move(config)));
}

SimTofScanner::SimTofScanner(SimTofScannerConfig config)
    : SimScanner(detail::scanner_parts(config, "simulated Riegl LMS-Z420i",
                                       DeviceKind::kTimeOfFlight, tof_capabilities(),
                                       {.angular_step_deg = config.scanner.angular_step_deg,
                                        .min_range_m = config.scanner.min_range_m,
                                        .max_range_m = config.scanner.max_range_m,
                                        .horizontal_field_deg = config.scanner.azimuth_span_deg,
                                        .vertical_field_deg = config.scanner.elevation_max_deg -
                                                              config.scanner.elevation_min_deg})),
      config_(std::move(config)),
      station_(config_.station) {}

std::string SimTofScanner::calibration_json() const {
    char json[256];
    std::snprintf(json, sizeof(json),
                  "{\"scene\": \"%s\", \"range_noise_sigma_m\": %g, \"azimuth_span_deg\": %g, "
                  "\"elevation_min_deg\": %g, \"elevation_max_deg\": %g}",
                  scene().name.c_str(), config_.scanner.range_noise_sigma_m,
                  config_.scanner.azimuth_span_deg, config_.scanner.elevation_min_deg,
                  config_.scanner.elevation_max_deg);
    return json;
}

Pose SimTofScanner::station_pose() const {
    const Pose T_world_block = block_pose(scene().placement, scene().block.size_m);
    return tripod_pose(T_world_block.translation(), station_.azimuth_deg, station_.distance_m,
                       station_.height_m);
}

Expected<Scan> SimTofScanner::capture_scan(const drivers::CaptureControl& control) {
    auto world = begin_capture();
    if (!world) return fail(world.error());
    detail::SimCaptureRun run(control, info().uri, faults());
    const drivers::DeviceSettings now = settings();
    TofScannerConfig scanner = config_.scanner;
    scanner.angular_step_deg = *now.angular_step_deg;
    scanner.min_range_m = *now.min_range_m;
    scanner.max_range_m = *now.max_range_m;
    // The sweep: its width from the first azimuth, its height about the configured centre.
    scanner.azimuth_span_deg = *now.horizontal_field_deg;
    const double centre_deg =
        0.5 * (config_.scanner.elevation_min_deg + config_.scanner.elevation_max_deg);
    scanner.elevation_min_deg = centre_deg - 0.5 * *now.vertical_field_deg;
    scanner.elevation_max_deg = centre_deg + 0.5 * *now.vertical_field_deg;
    scanner.seed = config_.scanner.seed + static_cast<std::uint64_t>(sequence());  // new noise
    const Pose T_world_scanner = station_pose();
    const TofSweepControl sweep{.keep_going = [&](double f) { return run.keep_going(f, "sweep"); }};
    auto result =
        simulate_tof_scan((*world)->caster, (*world)->albedos, T_world_scanner, scanner, sweep);
    // The end of the sweep is the last point where the device can go away or time out.
    const bool stopped = result ? !run.keep_going(1.0, "scan complete")
                                : result.error().code == ErrorCode::kCancelled;
    if (stopped) {
        if (run.unplugged()) set_unplugged();
        return fail(run.stop_reason());
    }
    if (!result) return fail(result.error().code, info().uri + ": " + result.error().message);
    Scan scan = std::move(result->scan);
    stamp(scan, T_world_scanner);
    station_.azimuth_deg += config_.advance_deg;
    return with_output_faults(std::move(scan));
}

}  // namespace anascan::sim
