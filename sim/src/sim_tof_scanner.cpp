#include "anascan/sim/sim_tof_scanner.hpp"

#include <cstdio>

#include "anascan/sim/viewpoints.hpp"
#include "sim_capture_run.hpp"

namespace anascan::sim {
namespace {

using drivers::CaptureControl;
using drivers::DeviceSettings;

drivers::Capabilities tof_capabilities() {
    drivers::Capabilities caps;
    caps.can_capture_scan = true;
    // 0.02 degrees keeps a full panorama under the simulator's 1e8 rays; the LMS-Z420i
    // goes finer, over smaller windows.
    caps.angular_step_deg = drivers::NumericRange{0.02, 5.0};
    caps.range_m = drivers::NumericRange{2.0, 800.0};
    return caps;
}

std::string scan_id(const std::string& uri, std::int64_t sequence) {
    char id[64];
    std::snprintf(id, sizeof(id), "-%06lld", static_cast<long long>(sequence));
    std::string name = uri.substr(uri.find(':') + 1);
    for (char& c : name)
        if (c == '/') c = '-';
    return "sim-" + name + id;
}

}  // namespace

std::unique_ptr<SimTofScanner> SimTofScanner::open(SimTofScannerConfig config) {
    if (!config.worlds) config.worlds = std::make_shared<SimWorldCache>();
    return std::unique_ptr<SimTofScanner>(new SimTofScanner(std::move(config)));
}

SimTofScanner::SimTofScanner(SimTofScannerConfig config)
    : config_(std::move(config)), station_(config_.station) {
    info_ =
        drivers::DeviceInfo{.uri = config_.uri,
                            .model = "simulated Riegl LMS-Z420i (scene " + config_.scene.name + ")",
                            .serial = "sim-tof",
                            .kind = DeviceKind::kTimeOfFlight,
                            .is_scanner = true};
    caps_ = tof_capabilities();
    settings_ = DeviceSettings{.angular_step_deg = config_.scanner.angular_step_deg,
                               .min_range_m = config_.scanner.min_range_m,
                               .max_range_m = config_.scanner.max_range_m};
}

Expected<void> SimTofScanner::configure(const DeviceSettings& requested) {
    if (closed_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
    const DeviceSettings merged = drivers::merge_settings(settings_, requested);
    if (auto ok = drivers::validate_settings(merged, caps_, info_.uri); !ok) return ok;
    settings_ = merged;
    return {};
}

std::string SimTofScanner::calibration_json() const {
    char json[256];
    std::snprintf(json, sizeof(json),
                  "{\"scene\": \"%s\", \"range_noise_sigma_m\": %g, \"azimuth_span_deg\": %g, "
                  "\"elevation_min_deg\": %g, \"elevation_max_deg\": %g}",
                  config_.scene.name.c_str(), config_.scanner.range_noise_sigma_m,
                  config_.scanner.azimuth_span_deg, config_.scanner.elevation_min_deg,
                  config_.scanner.elevation_max_deg);
    return json;
}

void SimTofScanner::close() { closed_ = true; }

Pose SimTofScanner::station_pose() const {
    const Pose T_world_block = block_pose(config_.scene.placement, config_.scene.block.size_m);
    return tripod_pose(T_world_block.translation(), station_.azimuth_deg, station_.distance_m,
                       station_.height_m);
}

void SimTofScanner::place_block(const BlockPlacement& placement) {
    config_.scene.placement = placement;
    world_.reset();
}

Expected<std::shared_ptr<const SimWorld>> SimTofScanner::world() {
    if (world_) return world_;
    auto world = config_.worlds->get(config_.scene);
    if (!world) return fail(world.error().code, info_.uri + ": " + world.error().message);
    world_ = *world;
    return world_;
}

Expected<Scan> SimTofScanner::capture_scan(const CaptureControl& control) {
    if (closed_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
    if (unplugged_) return fail(ErrorCode::kDisconnected, info_.uri + ": unplugged");
    auto world = this->world();
    if (!world) return fail(world.error());
    detail::SimCaptureRun run(control, info_.uri, config_.faults);
    TofScannerConfig scanner = config_.scanner;
    scanner.angular_step_deg = *settings_.angular_step_deg;
    scanner.min_range_m = *settings_.min_range_m;
    scanner.max_range_m = *settings_.max_range_m;
    scanner.seed = config_.scanner.seed + static_cast<std::uint64_t>(sequence_);  // new noise
    scanner.device_id = info_.uri;
    scanner.scan_id = scan_id(info_.uri, sequence_);
    const TofSweepControl sweep{.keep_going = [&](double f) { return run.keep_going(f, "sweep"); }};
    auto result =
        simulate_tof_scan((*world)->caster, (*world)->albedos, station_pose(), scanner, sweep);
    // The end of the sweep is the last point where the device can go away or time out.
    const bool stopped = result ? !run.keep_going(1.0, "scan complete")
                                : result.error().code == ErrorCode::kCancelled;
    if (stopped) {
        unplugged_ = run.unplugged();
        return fail(run.stop_reason());
    }
    if (!result) return fail(result.error());
    Scan scan = std::move(result->scan);
    scan.meta.sequence = sequence_++;
    scan.meta.settings_json = drivers::settings_to_json(settings_);
    station_.azimuth_deg += config_.advance_deg;
    return scan;
}

}  // namespace anascan::sim
