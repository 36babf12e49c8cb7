#pragma once
// A scripted V4L2 capture device for umockdev: answers the ioctls and read() of
// /dev/<node> as a small camera does (QUERYCAP, ENUM_FMT, ENUM_FRAMESIZES, G/S_FMT,
// QUERYCTRL, G/S_CTRL, REQBUFS, QBUF, DQBUF, STREAMON/OFF), with test-controlled
// frames, stalls (no frame: EAGAIN) and unplugs (ENODEV from then on).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "anascan/drivers/frame.hpp"
#include "mock_pixel.hpp"

struct v4l2_capability;
struct v4l2_format;
struct v4l2_control;
#include "umockdev_testbed.hpp"

namespace anascan::drivers::test {

struct MockV4l2Config {
    std::string node = "video0";  ///< /dev/video0, /sys/class/video4linux/video0.
    std::string card = "anascan mock depth camera";
    int width = 16;
    int height = 12;
    std::vector<PixelFormat> formats{PixelFormat::kZ16, PixelFormat::kGrey8, PixelFormat::kYuyv,
                                     PixelFormat::kMjpeg};
    bool can_read = true;   ///< V4L2_CAP_READWRITE.
    bool streaming = true;  ///< V4L2_CAP_STREAMING (user pointers).
    int exposure_min = 1;   ///< 100 µs units, as V4L2_CID_EXPOSURE_ABSOLUTE.
    int exposure_max = 1000;
    /// The image bytes of each frame (a camera seeing something); empty: mock_pixel.
    /// Called on umockdev's worker thread when the frame is taken (its exposure start).
    std::function<std::vector<std::uint8_t>()> frame_source;
    /// Streaming frames are delivered one call late, as from a driver's queue: each DQBUF
    /// returns the frame taken at the previous one (time-stamped then).
    bool one_frame_late = false;
};

/// Thread-safe: the test thread changes the behaviour while umockdev's worker thread
/// answers the device's calls.
class MockV4l2Camera {
public:
    MockV4l2Camera(Testbed& testbed, MockV4l2Config config);
    ~MockV4l2Camera();

    std::string dev_path() const { return "/dev/" + config_.node; }
    std::string uri() const { return "v4l2:" + dev_path(); }
    /// After `frames` more frames every call fails with ENODEV and the device leaves sysfs.
    void unplug_after(int frames) { unplug_after_ = frames; }
    void unplug_now();
    /// While stalled, no frame is ready (read/DQBUF: EAGAIN).
    void set_stalled(bool stalled) { stalled_ = stalled; }
    /// Every `every`-th frame (1: all) is garbage: half its bytes (0: none).
    void set_garbled(int every) { garbled_every_ = every; }
    /// While frozen, every frame repeats the bytes of the frame taken when it froze.
    void set_frozen(bool frozen) { frozen_ = frozen; }
    /// While busy (another program streams), S_FMT and REQBUFS fail with EBUSY.
    void set_busy(bool busy) { busy_ = busy; }
    std::uint64_t frames_sent() const { return frames_sent_.load(); }
    int streamon_count() const { return streamon_count_.load(); }
    int queued_buffers() const;
    int frame_rate_hz() const {
        std::lock_guard lock(mutex_);
        return rate_hz_;
    }

    // Called by the umockdev signal trampolines (worker thread).
    bool handle_ioctl(void* client);
    bool handle_read(void* client);

private:
    std::vector<std::uint8_t> render_frame(std::uint64_t sequence) const;
    /// The next frame's bytes (frozen or garbled as set); counts it sent.
    std::vector<std::uint8_t> next_bytes();
    /// A frame and the CLOCK_MONOTONIC time it was taken (streaming).
    struct Taken {
        std::vector<std::uint8_t> bytes;
        std::chrono::nanoseconds at{};
    };
    Taken take_frame();
    std::size_t image_bytes() const;
    bool next_frame_available();
    int handle_format_ioctl(unsigned long request, void* arg_data);
    int query_capability(v4l2_capability* cap) const;
    int enumerate(unsigned long request, void* arg_data) const;
    int set_or_get_format(bool set, v4l2_format* format);
    int exposure_control(bool set, v4l2_control* control);
    int dequeue_buffer(void* client, void* arg);
    int handle_buffer_ioctl(void* client, unsigned long request, void* arg);

    Testbed& testbed_;
    MockV4l2Config config_;
    std::string sysfs_path_;
    UMockdevIoctlBase* handler_ = nullptr;
    mutable std::mutex mutex_;
    PixelFormat format_;
    int exposure_ = 100;
    int rate_hz_ = 30;
    std::vector<unsigned long> queued_userptrs_;
    std::vector<std::uint32_t> queued_indices_;
    std::optional<Taken> pending_;  ///< one_frame_late: taken at the previous DQBUF.
    std::atomic<int> unplug_after_{-1};
    std::atomic<bool> unplugged_{false};
    std::atomic<bool> stalled_{false};
    std::atomic<bool> busy_{false};
    std::atomic<int> garbled_every_{0};
    std::atomic<bool> frozen_{false};
    std::optional<std::uint64_t> frozen_seq_;  // guarded by mutex_
    std::atomic<std::uint64_t> frames_sent_{0};
    std::atomic<int> streamon_count_{0};
};

}  // namespace anascan::drivers::test
