#include "anascan/sim/sim_camera.hpp"

#include <tbb/parallel_for.h>

#include <thread>

#include "sim_capture_run.hpp"

namespace anascan::sim {
namespace {

constexpr double kReferenceExposureUs = 10000.0;  ///< Renders with view.render.exposure_dn.

}  // namespace

SimCamera::SimCamera(SimCameraConfig config) : config_(std::move(config)) {
    info_ = {.uri = config_.uri,
             .model = "simulated camera",
             .serial = "sim",
             .kind = DeviceKind::kUnknown,
             .is_camera = true};
    const drivers::StreamProfile profile{config_.width_px, config_.height_px,
                                         drivers::PixelFormat::kGrey8, 0.0};
    caps_.can_stream = true;
    caps_.profiles = {profile};
    caps_.exposure_us = drivers::NumericRange{1000.0, 40000.0};
    settings_ = {.profile = profile, .exposure_us = kReferenceExposureUs};
}

Expected<void> SimCamera::configure(const drivers::DeviceSettings& requested) {
    if (closed_ || gone_) return fail(ErrorCode::kDisconnected, info_.uri + ": gone");
    if (auto ok = drivers::validate_settings(requested, caps_, info_.uri); !ok) return ok;
    settings_ = drivers::merge_settings(settings_, requested);
    ahead_of_.reset();  // rendered with the old exposure
    return {};
}

void SimCamera::close() {
    streaming_ = false;
    closed_ = true;
    surface_.reset();
    last_.reset();
}

void SimCamera::set_view(SimCameraView view) {
    view_ = std::move(view);
    surface_.reset();
    last_.reset();
    ahead_of_.reset();
}

Expected<void> SimCamera::check_usable() {
    if (closed_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
    if (gone_) return fail(ErrorCode::kDisconnected, info_.uri + ": unplugged");
    return {};
}

Expected<void> SimCamera::start_stream() {
    if (auto ok = check_usable(); !ok) return ok;
    if (!view_ || !config_.screen)
        return fail(ErrorCode::kInvalidArgument, info_.uri + ": no scene to look at");
    streaming_ = true;
    rendered_ = 0;
    return {};
}

bool SimCamera::stalled() const {
    return (config_.faults && config_.faults->stalled.load()) ||
           (device_faults_ && device_faults_->stalled.load());
}

Expected<drivers::Frame> SimCamera::next_frame(std::chrono::milliseconds timeout) {
    if (auto ok = check_usable(); !ok) return fail(ok.error());
    if (!streaming_) return fail(ErrorCode::kInvalidArgument, info_.uri + ": not streaming");
    if (stalled()) {  // a silent camera: nothing within the timeout
        std::this_thread::sleep_for(timeout);
        return fail(ErrorCode::kTimeout,
                    info_.uri + ": no frame within " + std::to_string(timeout.count()) + " ms");
    }
    gone_ = detail::take_from_budget(config_.faults.get());
    if (gone_) return fail(ErrorCode::kDisconnected, info_.uri + ": unplugged");
    const SimProjectorScreen::Showing showing = config_.screen->now();
    if (config_.stale_frame_after_switch && last_ && last_serial_ != showing.serial) {
        last_serial_ = showing.serial;  // the queued frame, exposed before the switch
        drivers::Frame stale = *last_;
        stale.sequence = sequence_++;
        return stale;
    }
    drivers::Frame frame = render(drivers::steady_now(), showing);
    if (config_.stale_frame_after_switch) {
        last_ = frame;
        last_serial_ = showing.serial;
    }
    return frame;
}

cv::Mat SimCamera::image_of(const SimProjectorScreen::Showing& showing,
                            const StructuredLightRenderConfig& render) {
    if (!surface_)
        surface_ = trace_camera_surface(view_->world->caster, view_->world->albedos, view_->camera,
                                        view_->projector, render);
    const auto loaded = config_.screen->loaded();
    const bool in_sequence = showing.image && loaded && showing.index < loaded->size() &&
                             (*loaded)[showing.index] == showing.image;
    if (!in_sequence)  // dark, or an image from elsewhere: render it now
        return render_camera_image(*surface_, showing.image ? *showing.image : cv::Mat(), render,
                                   camera_noise_seed(render, config_.camera_index, rendered_++));
    if (ahead_of_ != loaded) {
        ahead_.assign(loaded->size(), cv::Mat());
        tbb::parallel_for(std::size_t{0}, loaded->size(), [&](std::size_t i) {
            ahead_[i] = render_camera_image(*surface_, *(*loaded)[i], render,
                                            camera_noise_seed(render, config_.camera_index, i));
        });
        ahead_of_ = loaded;
    }
    ++rendered_;
    return ahead_[showing.index];
}

drivers::Frame SimCamera::render(std::chrono::nanoseconds start,
                                 const SimProjectorScreen::Showing& showing) {
    StructuredLightRenderConfig render = view_->render;
    render.exposure_dn *= *settings_.exposure_us / kReferenceExposureUs;
    const cv::Mat image = image_of(showing, render);
    drivers::Frame frame;
    frame.width = image.cols;
    frame.height = image.rows;
    frame.format = drivers::PixelFormat::kGrey8;
    frame.stride_bytes = static_cast<std::size_t>(image.cols);
    frame.sequence = sequence_++;
    frame.timestamp_ns = start;
    frame.data.assign(image.data, image.data + image.total());
    return frame;
}

}  // namespace anascan::sim
