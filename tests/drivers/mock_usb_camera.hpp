#pragma once
// A scripted USB device for umockdev: the sysfs entry libusb enumerates (descriptors of
// one vendor interface with bulk endpoints 0x81/0x02) and the usbfs ioctls libusb issues
// (GET_CAPABILITIES, GETDRIVER, CLAIM/RELEASEINTERFACE, SUBMITURB, REAPURB[NDELAY],
// DISCARDURB). It speaks the bulk-frame protocol of usb_bulk_camera.hpp.

#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include "umockdev_testbed.hpp"

typedef struct _UMockdevIoctlData UMockdevIoctlData;

namespace anascan::drivers::test {

struct MockUsbConfig {
    std::uint16_t vendor_id = 0x1209;
    std::uint16_t product_id = 0x0001;
    int width = 32;  ///< Must match the supported-device table row.
    int height = 24;
    int bus = 1;
    int address = 2;
};

/// Thread-safe: the test thread changes the behaviour while umockdev's worker answers.
class MockUsbCamera {
public:
    MockUsbCamera(Testbed& testbed, MockUsbConfig config);
    ~MockUsbCamera();

    std::string uri() const;
    std::string dev_path() const;
    /// After `frames` more frames every call fails with ENODEV.
    void unplug_after(int frames) { unplug_after_ = frames; }
    /// Removes the device from sysfs (and fails every call), as an unplug does.
    void unplug_now();
    void set_stalled(bool stalled) { stalled_ = stalled; }
    /// Every `every`-th frame (1: all) is garbage: its header's magic is wrong (0: none).
    void set_garbled(int every) { garbled_every_ = every; }
    /// While frozen, every frame repeats the pixels of the frame sent when it froze.
    void set_frozen(bool frozen) { frozen_ = frozen; }
    bool streaming() const { return streaming_.load(); }
    int exposure_units() const { return exposure_.load(); }
    std::uint64_t frames_sent() const { return frames_sent_.load(); }

    bool handle_ioctl(void* client);

private:
    struct Urb {
        UMockdevIoctlData* urb = nullptr;
        UMockdevIoctlData* buffer = nullptr;
    };
    int submit(UMockdevIoctlData* arg);
    int reap(UMockdevIoctlData* arg);
    int discard(unsigned long client_addr);
    bool complete_urb(Urb& urb);
    void fill_frame(Urb& urb);

    Testbed& testbed_;
    MockUsbConfig config_;
    std::string sysfs_path_;
    UMockdevIoctlBase* handler_ = nullptr;
    std::mutex mutex_;
    std::deque<Urb> pending_;
    std::deque<Urb> discarded_;
    std::atomic<int> unplug_after_{-1};
    std::atomic<bool> unplugged_{false};
    std::atomic<bool> stalled_{false};
    std::atomic<int> garbled_every_{0};
    std::atomic<bool> frozen_{false};
    std::optional<std::uint64_t> frozen_seq_;  // guarded by mutex_
    std::atomic<bool> streaming_{false};
    std::atomic<int> exposure_{100};
    std::atomic<std::uint64_t> frames_sent_{0};
};

}  // namespace anascan::drivers::test
