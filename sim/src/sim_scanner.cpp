#include "anascan/sim/sim_scanner.hpp"

#include <cstdio>
#include <limits>

namespace anascan::sim {

SimScanner::SimScanner(SimScannerParts parts)
    : info_(std::move(parts.info)),
      caps_(std::move(parts.caps)),
      settings_(std::move(parts.settings)),
      scene_(std::move(parts.scene)),
      worlds_(parts.worlds ? std::move(parts.worlds) : std::make_shared<SimWorldCache>()),
      faults_(std::move(parts.faults)) {}

Expected<void> SimScanner::configure(const drivers::DeviceSettings& requested) {
    if (closed_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
    const drivers::DeviceSettings merged = drivers::merge_settings(settings_, requested);
    if (auto ok = drivers::validate_settings(merged, caps_, info_.uri); !ok) return ok;
    settings_ = merged;
    return {};
}

void SimScanner::place_block(const BlockPlacement& placement) {
    scene_.placement = placement;
    world_.reset();
}

Expected<std::shared_ptr<const SimWorld>> SimScanner::world() {
    if (world_) return world_;
    auto world = worlds_->get(scene_);
    if (!world) return fail(world.error().code, info_.uri + ": " + world.error().message);
    world_ = *world;
    return world_;
}

Expected<std::shared_ptr<const SimWorld>> SimScanner::begin_capture() {
    if (closed_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
    if (unplugged_) return fail(ErrorCode::kDisconnected, info_.uri + ": unplugged");
    return world();
}

void SimScanner::stamp(Scan& scan, const Pose& T_world_scan) {
    // "sim:tof/small-block" -> "sim-tof-small-block-000003"
    std::string id = "sim-" + info_.uri.substr(info_.uri.find(':') + 1);
    for (char& c : id)
        if (c == '/') c = '-';
    char number[32];
    std::snprintf(number, sizeof(number), "-%06lld", static_cast<long long>(sequence_));
    scan.meta.id = id + number;
    scan.meta.sequence = sequence_++;
    scan.meta.device_id = info_.uri;
    scan.meta.device_kind = info_.kind;
    scan.meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
    scan.meta.T_world_scan = T_world_scan;
    scan.meta.settings_json = drivers::settings_to_json(settings_);
}

Scan SimScanner::with_output_faults(Scan scan) {
    if (!faults_) return scan;
    if (faults_->frozen.load() && last_delivered_) return *last_delivered_;
    int left = faults_->garbage_scans.load();
    while (left > 0 && !faults_->garbage_scans.compare_exchange_weak(left, left - 1)) {
    }
    if (left > 0) {
        for (Eigen::Vector3f& p : scan.cloud.positions)
            p.setConstant(std::numeric_limits<float>::quiet_NaN());
    }
    last_delivered_ = scan;
    return scan;
}

}  // namespace anascan::sim
