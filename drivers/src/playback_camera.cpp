// A recording played back as a camera.
#include <optional>

#include "anascan/drivers/recording.hpp"
#include "frame_file.hpp"
#include "recording_manifest.hpp"

namespace anascan::drivers {
namespace {

/// Not thread-safe (see Camera).
class PlaybackCamera final : public Camera {
public:
    PlaybackCamera(RecordingManifest manifest, PlaybackConfig config)
        : manifest_(as_played_back(std::move(manifest), config.folder)),
          config_(std::move(config)) {
        // A recording replays what was recorded: its only stream is the recorded one.
        if (manifest_.settings.profile)
            manifest_.capabilities.profiles = {*manifest_.settings.profile};
    }
    const DeviceInfo& info() const override { return manifest_.device; }
    const Capabilities& capabilities() const override { return manifest_.capabilities; }
    DeviceSettings settings() const override { return manifest_.settings; }
    std::string calibration_json() const override { return manifest_.calibration_json; }
    Expected<void> configure(const DeviceSettings& requested) override {
        return configure_played_back(manifest_, closed_, requested);
    }
    void close() override {
        reader_.reset();
        closed_ = true;
    }
    Expected<void> start_stream() override {
        if (closed_) return fail(ErrorCode::kDisconnected, info().uri + ": closed");
        auto reader = FrameFileReader::open(config_.folder / "frames.bin");
        if (!reader) return fail(reader.error());
        reader_.emplace(std::move(*reader));
        return {};
    }
    Expected<Frame> next_frame(std::chrono::milliseconds) override {
        if (!reader_) return fail(ErrorCode::kInvalidArgument, info().uri + ": not streaming");
        Expected<Frame> frame = reader_->next();
        if (!frame && config_.loop && !reader_->stopped_early()) {
            reader_->rewind();
            frame = reader_->next();
        }
        return frame;
    }
    void stop_stream() override { reader_.reset(); }

private:
    RecordingManifest manifest_;
    PlaybackConfig config_;
    std::optional<FrameFileReader> reader_;
    bool closed_ = false;
};

}  // namespace

Expected<std::unique_ptr<Camera>> open_playback(const PlaybackConfig& config) {
    auto manifest = read_manifest(config.folder);
    if (!manifest) return fail(manifest.error());
    if (!manifest->device.is_camera) {
        return fail(ErrorCode::kUnsupported,
                    config.folder.string() + ": a scanner recording, not a camera recording");
    }
    return std::unique_ptr<Camera>(new PlaybackCamera(std::move(*manifest), config));
}

Backend make_playback_backend() {
    return Backend{.scheme = "playback",
                   .description = "recorded cameras and scanners, e.g. playback:/data/rec-0001",
                   .enumerate = [] { return std::vector<DeviceInfo>{}; },
                   .open = [](const DeviceUri& uri) -> Expected<std::unique_ptr<Device>> {
                       return open_playback_device({.folder = uri.target});
                   }};
}

}  // namespace anascan::drivers
