#pragma once
/// \file
/// The simulated projector of sim:structured-light: a drivers::PatternOutput that receives
/// the pattern images and puts the one shown on a SimProjectorScreen, where the simulated
/// cameras (sim_camera.hpp) see it lighting the scene.

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "anascan/drivers/pattern_output.hpp"
#include "anascan/sim/sim_device_faults.hpp"

namespace anascan::sim {

/// What the projector shows now. Thread-safe (a mutex): the projector writes, the cameras
/// read.
class SimProjectorScreen {
public:
    using Images = std::vector<std::shared_ptr<const cv::Mat>>;
    struct Showing {
        std::shared_ptr<const cv::Mat> image;  ///< CV_8UC1; null: dark.
        std::chrono::nanoseconds shown_at{};   ///< Host steady clock.
        std::uint64_t serial = 0;              ///< Counts the patterns shown.
        std::size_t index = 0;                 ///< Of `image` in loaded().
    };
    /// The sequence the projector holds (a camera may render ahead of it).
    void load(std::shared_ptr<const Images> images);
    std::shared_ptr<const Images> loaded() const;
    void show(std::size_t index, std::chrono::nanoseconds shown_at);
    Showing now() const;

private:
    mutable std::mutex mutex_;
    std::shared_ptr<const Images> loaded_;
    Showing showing_;
};

/// Not thread-safe (see drivers::PatternOutput). `faults`: unplug_after_captures counts
/// the patterns shown before it goes away (then every show fails with kDisconnected).
class SimProjector final : public drivers::PatternOutput {
public:
    SimProjector(std::string name, int width_px, int height_px,
                 std::shared_ptr<SimProjectorScreen> screen,
                 std::shared_ptr<SimDeviceFaults> faults);

    std::string name() const override { return name_; }
    int width_px() const override { return width_; }
    int height_px() const override { return height_; }
    Expected<void> load(std::span<const drivers::Pattern> patterns) override;
    Expected<std::chrono::nanoseconds> show(std::size_t index) override;

private:
    std::string name_;
    int width_;
    int height_;
    std::shared_ptr<SimProjectorScreen> screen_;
    std::shared_ptr<SimDeviceFaults> faults_;
    std::size_t loaded_count_ = 0;
    bool gone_ = false;
};

}  // namespace anascan::sim
