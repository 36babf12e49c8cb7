// The persistence thread of a capture session: a scan is acknowledged only once its file
// and its row are durable (SessionStore::save_scan).
#include <cstdio>

#include "capture/impl.hpp"

namespace anascan::acquisition {

void CaptureSession::Impl::save_loop() {
    while (auto item = to_save.pop()) save_one(std::move(**item));
}

void CaptureSession::Impl::save_one(CapturedScan captured) {
    const std::string device = captured.scan.meta.device_id;
    auto record = store->save_scan(captured.scan, captured.true_pose);
    if (!record) {
        const std::string message = "scan NOT saved: " + record.error().message;
        (void)store->add_event("save-failed", device, message);
        emit({.kind = SessionEventKind::kSaveFailed, .device = device, .message = message});
        captured.acknowledged.set_value(fail(record.error()));
        end_work();
        return;
    }
    if (captured.turned_over) (void)store->mark_turned_over(record->seq - 1);
    captured.acknowledged.set_value(record->seq);
    char message[256];
    std::snprintf(message, sizeof(message), "saved scan %lld (%zu points, %s)",
                  static_cast<long long>(record->seq), record->point_count, record->file.c_str());
    emit({.kind = SessionEventKind::kSaved,
          .seq = record->seq,
          .device = device,
          .message = message,
          .count = record->point_count});
    if (!config.register_live) {
        end_work();
        return;
    }
    SavedScan saved{.seq = record->seq,
                    .turned_over = captured.turned_over,
                    .acknowledged_at = record->acknowledged_at};
    // Past the bound the worker reads the scan back: memory stays bounded when the worker
    // falls behind, and the scanner never waits for it.
    if (registration_items_with_points.load() < config.registration_queue_capacity) {
        ++registration_items_with_points;
        saved.scan = std::make_shared<const Scan>(std::move(captured.scan));
    }
    if (!to_register.push(std::move(saved))) end_work();
}

}  // namespace anascan::acquisition
