// The recording decorator for scanners, and recorded scans played back as a scanner.
#include "anascan/drivers/recording.hpp"
#include "recording_manifest.hpp"
#include "scan_record.hpp"

namespace anascan::drivers {
namespace {

/// Not thread-safe (see Scanner).
class RecordingScanner final : public Scanner {
public:
    RecordingScanner(std::unique_ptr<Scanner> inner, RecordingConfig config)
        : inner_(std::move(inner)), config_(std::move(config)) {}
    const DeviceInfo& info() const override { return inner_->info(); }
    const Capabilities& capabilities() const override { return inner_->capabilities(); }
    DeviceSettings settings() const override { return inner_->settings(); }
    std::string calibration_json() const override { return inner_->calibration_json(); }
    Expected<void> configure(const DeviceSettings& requested) override {
        if (auto ok = inner_->configure(requested); !ok) return ok;
        return write_current_manifest();
    }
    void close() override { inner_->close(); }
    Expected<Scan> capture_scan(const CaptureControl& control) override {
        Expected<Scan> scan = inner_->capture_scan(control);
        if (!scan) return scan;
        if (auto ok = write_scan_record(config_.folder / "scans", count_, *scan); !ok)
            return fail(ok.error());
        ++count_;
        return scan;
    }
    Expected<void> write_current_manifest() {
        return write_manifest(config_.folder,
                              {info(), capabilities(), settings(), calibration_json()});
    }

private:
    std::unique_ptr<Scanner> inner_;
    RecordingConfig config_;
    std::size_t count_ = 0;
};

/// Not thread-safe (see Scanner).
class PlaybackScanner final : public Scanner {
public:
    PlaybackScanner(RecordingManifest manifest, const PlaybackConfig& config)
        : manifest_(as_played_back(std::move(manifest), config.folder)),
          records_(list_scan_records(config.folder / "scans")) {}
    const DeviceInfo& info() const override { return manifest_.device; }
    const Capabilities& capabilities() const override { return manifest_.capabilities; }
    DeviceSettings settings() const override { return manifest_.settings; }
    std::string calibration_json() const override { return manifest_.calibration_json; }
    Expected<void> configure(const DeviceSettings& requested) override {
        return configure_played_back(manifest_, closed_, requested);
    }
    void close() override { closed_ = true; }
    Expected<Scan> capture_scan(const CaptureControl& control) override {
        if (closed_) return fail(ErrorCode::kDisconnected, info().uri + ": closed");
        if (control.stop.stop_requested())
            return fail(ErrorCode::kCancelled, info().uri + ": cancelled");
        if (next_ >= records_.size())
            return fail(ErrorCode::kEmpty, info().uri + ": end of recording");
        auto scan = read_scan_record(records_[next_++]);
        if (scan && control.on_progress) control.on_progress({1.0, "scan " + scan->meta.id});
        return scan;
    }

private:
    RecordingManifest manifest_;
    std::vector<std::filesystem::path> records_;
    std::size_t next_ = 0;
    bool closed_ = false;
};

}  // namespace

Expected<std::unique_ptr<Scanner>> record_scanner(std::unique_ptr<Scanner> scanner,
                                                  const RecordingConfig& config) {
    if (auto ok = prepare_recording_folder(config.folder); !ok) return fail(ok.error());
    auto recorder = std::make_unique<RecordingScanner>(std::move(scanner), config);
    if (auto ok = recorder->write_current_manifest(); !ok) return fail(ok.error());
    return std::unique_ptr<Scanner>(std::move(recorder));
}

Expected<std::unique_ptr<Scanner>> open_scan_playback(const PlaybackConfig& config) {
    auto manifest = read_manifest(config.folder);
    if (!manifest) return fail(manifest.error());
    if (!manifest->device.is_scanner) {
        return fail(ErrorCode::kUnsupported,
                    config.folder.string() + ": a camera recording, not a scanner recording");
    }
    return std::unique_ptr<Scanner>(new PlaybackScanner(std::move(*manifest), config));
}

Expected<std::unique_ptr<Device>> open_playback_device(const PlaybackConfig& config) {
    auto manifest = read_manifest(config.folder);
    if (!manifest) return fail(manifest.error());
    if (manifest->device.is_scanner) {
        auto s = open_scan_playback(config);
        if (!s) return fail(s.error());
        return std::unique_ptr<Device>(std::move(*s));
    }
    auto c = open_playback(config);
    if (!c) return fail(c.error());
    return std::unique_ptr<Device>(std::move(*c));
}

}  // namespace anascan::drivers
