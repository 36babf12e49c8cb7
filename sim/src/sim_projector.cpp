#include "anascan/sim/sim_projector.hpp"

#include "sim_capture_run.hpp"

namespace anascan::sim {

void SimProjectorScreen::show(std::shared_ptr<const cv::Mat> image,
                              std::chrono::nanoseconds shown_at) {
    std::lock_guard lock(mutex_);
    showing_ = {std::move(image), shown_at, showing_.serial + 1};
}

SimProjectorScreen::Showing SimProjectorScreen::now() const {
    std::lock_guard lock(mutex_);
    return showing_;
}

SimProjector::SimProjector(std::string name, int width_px, int height_px,
                           std::shared_ptr<SimProjectorScreen> screen,
                           std::shared_ptr<SimDeviceFaults> faults)
    : name_(std::move(name)),
      width_(width_px),
      height_(height_px),
      screen_(std::move(screen)),
      faults_(std::move(faults)) {}

Expected<void> SimProjector::load(std::span<const drivers::Pattern> patterns) {
    if (auto ok = drivers::check_patterns(patterns, width_, height_, name_); !ok) return ok;
    images_.clear();
    for (const drivers::Pattern& p : patterns) {
        cv::Mat image(p.height, p.width, CV_8UC1);
        std::copy(p.grey.begin(), p.grey.end(), image.data);
        images_.push_back(std::make_shared<const cv::Mat>(std::move(image)));
    }
    return {};
}

Expected<std::chrono::nanoseconds> SimProjector::show(std::size_t index) {
    if (auto ok = drivers::check_pattern_index(index, images_.size(), name_); !ok)
        return fail(ok.error());
    gone_ = gone_ || detail::take_from_budget(faults_.get());
    if (gone_) return fail(ErrorCode::kDisconnected, name_ + ": went away (unplugged)");
    const std::chrono::nanoseconds shown_at = drivers::steady_now();
    screen_->show(images_[index], shown_at);
    return shown_at;
}

}  // namespace anascan::sim
