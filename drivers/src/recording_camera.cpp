// The recording decorator: a Camera that forwards to another and appends its frames.
#include <optional>

#include "anascan/drivers/recording.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "frame_file.hpp"
#include "recording_manifest.hpp"

namespace anascan::drivers {
namespace {

/// Not thread-safe (see Camera).
class RecordingCamera final : public Camera {
public:
    RecordingCamera(std::unique_ptr<Camera> inner, RecordingConfig config)
        : inner_(std::move(inner)), config_(std::move(config)) {}
    ~RecordingCamera() override { close(); }

    const DeviceInfo& info() const override { return inner_->info(); }
    const Capabilities& capabilities() const override { return inner_->capabilities(); }
    DeviceSettings settings() const override { return inner_->settings(); }
    std::string calibration_json() const override { return inner_->calibration_json(); }
    Expected<void> configure(const DeviceSettings& requested) override {
        return inner_->configure(requested);
    }
    void close() override {
        stop_stream();
        inner_->close();
    }

    // The manifest is written at stream start, so it holds the settings of the frames.
    Expected<void> start_stream() override {
        if (!writer_) {
            RecordingManifest m{info(), capabilities(), settings(), calibration_json()};
            if (auto ok = write_manifest(config_.folder, m); !ok) return ok;
            auto writer =
                FrameFileWriter::create(config_.folder / "frames.bin", config_.fsync_every_frames);
            if (!writer) return fail(writer.error());
            writer_.emplace(std::move(*writer));
        }
        return inner_->start_stream();
    }
    Expected<Frame> next_frame(std::chrono::milliseconds timeout) override {
        Expected<Frame> frame = inner_->next_frame(timeout);
        if (frame && writer_) {
            if (auto ok = writer_->append(*frame); !ok) return fail(ok.error());
        }
        return frame;
    }
    void stop_stream() override {
        inner_->stop_stream();
        if (writer_) (void)writer_->flush();
    }

private:
    std::unique_ptr<Camera> inner_;
    RecordingConfig config_;
    std::optional<FrameFileWriter> writer_;
};

}  // namespace

Expected<std::unique_ptr<Camera>> record_camera(std::unique_ptr<Camera> camera,
                                                const RecordingConfig& config) {
    if (auto ok = prepare_recording_folder(config.folder); !ok) return fail(ok.error());
    return std::unique_ptr<Camera>(new RecordingCamera(std::move(camera), config));
}

}  // namespace anascan::drivers
