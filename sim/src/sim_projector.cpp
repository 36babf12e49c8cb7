#include "anascan/sim/sim_projector.hpp"

#include "sim_capture_run.hpp"

namespace anascan::sim {

void SimProjectorScreen::load(std::shared_ptr<const Images> images) {
    std::lock_guard lock(mutex_);
    loaded_ = std::move(images);
}

std::shared_ptr<const SimProjectorScreen::Images> SimProjectorScreen::loaded() const {
    std::lock_guard lock(mutex_);
    return loaded_;
}

void SimProjectorScreen::show(std::size_t index, std::chrono::nanoseconds shown_at) {
    std::lock_guard lock(mutex_);
    showing_ = {(*loaded_)[index], shown_at, showing_.serial + 1, index};
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
    auto images = std::make_shared<SimProjectorScreen::Images>();
    for (const drivers::Pattern& p : patterns) {
        cv::Mat image(p.height, p.width, CV_8UC1);
        std::copy(p.grey.begin(), p.grey.end(), image.data);
        images->push_back(std::make_shared<const cv::Mat>(std::move(image)));
    }
    loaded_count_ = images->size();
    screen_->load(std::move(images));
    return {};
}

Expected<std::chrono::nanoseconds> SimProjector::show(std::size_t index) {
    if (auto ok = drivers::check_pattern_index(index, loaded_count_, name_); !ok)
        return fail(ok.error());
    gone_ = gone_ || detail::take_from_budget(faults_.get());
    if (gone_) return fail(ErrorCode::kDisconnected, name_ + ": went away (unplugged)");
    const std::chrono::nanoseconds shown_at = drivers::steady_now();
    screen_->show(index, shown_at);
    return shown_at;
}

}  // namespace anascan::sim
