#include "mock_usb_camera.hpp"

#include <linux/usbdevice_fs.h>
#include <sys/ioctl.h>
#include <umockdev.h>

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>

#include "anascan/drivers/frame.hpp"
#include "anascan/drivers/usb_bulk_camera.hpp"
#include "mock_pixel.hpp"

namespace anascan::drivers::test {
namespace {

gboolean on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    return static_cast<MockUsbCamera*>(self)->handle_ioctl(client);
}

std::string hex16(std::uint16_t v) {
    return std::string{"0123456789abcdef"[v >> 4 & 15], "0123456789abcdef"[v & 15],
                       "0123456789abcdef"[v >> 12 & 15], "0123456789abcdef"[v >> 8 & 15]};
}

// Device descriptor, one configuration, one vendor interface, bulk IN 0x81 and OUT 0x02.
std::string descriptors_hex(const MockUsbConfig& c) {
    return "1201000200000040" + hex16(c.vendor_id) + hex16(c.product_id) + "0001000000" + "01" +
           "0902200001010080320904000002ff0000000705810200020007050202000200";
}

}  // namespace

MockUsbCamera::MockUsbCamera(Testbed& testbed, MockUsbConfig config)
    : testbed_(testbed), config_(config) {
    char ids[64];
    std::snprintf(ids, sizeof(ids), "%04x\nA: idProduct=%04x", config_.vendor_id,
                  config_.product_id);
    char node[32];
    std::snprintf(node, sizeof(node), "bus/usb/%03d/%03d", config_.bus, config_.address);
    sysfs_path_ =
        testbed_.add_from_string("P: /devices/pci0000:00/0000:00:14.0/usb1/1-" +
                                 std::to_string(config_.address) + "\nN: " + std::string(node) +
                                 "\nE: SUBSYSTEM=usb\nE: DEVTYPE=usb_device\nE: DEVNAME=/dev/" +
                                 node + "\nE: BUSNUM=" + std::string(node).substr(8, 3) +
                                 "\nE: DEVNUM=" + std::string(node).substr(12, 3) +
                                 "\nA: busnum=" + std::to_string(config_.bus) +
                                 "\nA: devnum=" + std::to_string(config_.address) +
                                 "\nA: speed=480\nA: bConfigurationValue=1\nA: idVendor=" + ids +
                                 "\nH: descriptors=" + descriptors_hex(config_) + "\n");
    handler_ = umockdev_ioctl_base_new();
    g_signal_connect(handler_, "handle-ioctl", G_CALLBACK(on_ioctl), this);
    testbed_.attach(dev_path(), handler_);
}

MockUsbCamera::~MockUsbCamera() {
    testbed_.detach(dev_path());
    g_object_unref(handler_);
    for (auto* list : {&pending_, &discarded_}) {
        for (Urb& u : *list) {
            g_object_unref(u.urb);
            if (u.buffer) g_object_unref(u.buffer);
        }
    }
}

std::string MockUsbCamera::uri() const {
    char text[16];
    std::snprintf(text, sizeof(text), "usb:%04x:%04x", config_.vendor_id, config_.product_id);
    return text;
}

std::string MockUsbCamera::dev_path() const {
    char node[32];
    std::snprintf(node, sizeof(node), "/dev/bus/usb/%03d/%03d", config_.bus, config_.address);
    return node;
}

void MockUsbCamera::unplug_now() {
    unplugged_ = true;
    testbed_.uevent(sysfs_path_, "remove");  // what udev (and libusb hotplug) listens to
    testbed_.remove(sysfs_path_);
}

int MockUsbCamera::submit(UMockdevIoctlData* arg) {
    GError* error = nullptr;
    UMockdevIoctlData* urb = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), &error);
    if (urb == nullptr) return EFAULT;  // our reference is kept until reaped
    auto* u = reinterpret_cast<usbdevfs_urb*>(urb->data);
    UMockdevIoctlData* buffer = nullptr;
    if (u->buffer_length > 0) {
        buffer = umockdev_ioctl_data_resolve(urb, offsetof(usbdevfs_urb, buffer), u->buffer_length,
                                             &error);
    }
    pending_.push_back({urb, buffer});
    return 0;
}

// Control transfers answer at once; bulk IN waits for a frame (streaming, not stalled).
bool MockUsbCamera::complete_urb(Urb& urb) {
    auto* u = reinterpret_cast<usbdevfs_urb*>(urb.urb->data);
    if (u->type == USBDEVFS_URB_TYPE_CONTROL) {
        const std::uint8_t* setup = urb.buffer->data;
        const std::uint16_t value = static_cast<std::uint16_t>(setup[2] | setup[3] << 8);
        if (setup[1] == usb_bulk::kRequestStreaming) streaming_ = value != 0;
        if (setup[1] == usb_bulk::kRequestExposure) exposure_ = value;
        u->status = 0;
        u->actual_length = 0;
        return true;
    }
    if (u->endpoint != usb_bulk::kFrameEndpoint || !streaming_ || stalled_) return false;
    if (unplug_after_.load() == 0) {
        unplugged_ = true;
        return false;
    }
    if (unplug_after_.load() > 0) --unplug_after_;
    fill_frame(urb);
    return true;
}

void MockUsbCamera::fill_frame(Urb& urb) {
    auto* u = reinterpret_cast<usbdevfs_urb*>(urb.urb->data);
    const std::uint64_t sent = frames_sent_++;
    if (!frozen_) frozen_seq_.reset();
    if (frozen_ && !frozen_seq_) frozen_seq_ = sent;
    const std::uint64_t seq = frozen_seq_.value_or(sent);
    std::uint8_t* out = urb.buffer->data;
    const std::size_t need = usb_bulk::kHeaderBytes + 2u * config_.width * config_.height;
    std::memset(out, 0, static_cast<std::size_t>(u->buffer_length));
    std::memcpy(out, "AFRM", 4);
    const auto w = static_cast<std::uint16_t>(config_.width),
               h = static_cast<std::uint16_t>(config_.height);
    const auto s = static_cast<std::uint32_t>(seq);
    std::memcpy(out + 4, &w, 2);
    std::memcpy(out + 6, &h, 2);
    out[8] = static_cast<std::uint8_t>(PixelFormat::kZ16);
    std::memcpy(out + 12, &s, 4);
    for (int r = 0; r < config_.height; ++r) {
        for (int c = 0; c < config_.width; ++c) {
            const std::uint16_t v = mock_pixel(r, c, seq);
            std::memcpy(out + usb_bulk::kHeaderBytes + 2 * (r * config_.width + c), &v, 2);
        }
    }
    const int every = garbled_every_.load();
    if (every > 0 && (sent + 1) % static_cast<std::uint64_t>(every) == 0)
        std::memcpy(out, "XXXX", 4);
    u->status = 0;
    u->actual_length =
        static_cast<int>(std::min<std::size_t>(need, static_cast<std::size_t>(u->buffer_length)));
}

int MockUsbCamera::reap(UMockdevIoctlData* arg) {
    Urb done;
    if (!discarded_.empty()) {
        done = discarded_.front();
        discarded_.pop_front();
        reinterpret_cast<usbdevfs_urb*>(done.urb->data)->status = -ENOENT;
    } else if (unplugged_) {
        // As the kernel does after a disconnect: every pending URB is reapable with
        // -ESHUTDOWN, then reaping fails with ENODEV.
        if (pending_.empty()) return ENODEV;
        done = pending_.front();
        pending_.pop_front();
        auto* u = reinterpret_cast<usbdevfs_urb*>(done.urb->data);
        u->status = -ESHUTDOWN;
        u->actual_length = 0;
    } else {
        auto it = pending_.begin();
        while (it != pending_.end() && !complete_urb(*it)) ++it;
        if (it == pending_.end()) return EAGAIN;
        done = *it;
        pending_.erase(it);
    }
    umockdev_ioctl_data_set_ptr(arg, 0, done.urb);
    g_object_unref(done.urb);  // the reap argument holds it now
    if (done.buffer) g_object_unref(done.buffer);
    return 0;
}

int MockUsbCamera::discard(unsigned long client_addr) {
    for (auto it = pending_.begin(); it != pending_.end(); ++it) {
        if (it->urb->client_addr == client_addr) {
            discarded_.push_back(*it);
            pending_.erase(it);
            return 0;
        }
    }
    return EINVAL;
}

bool MockUsbCamera::handle_ioctl(void* c) {
    auto* client = static_cast<UMockdevIoctlClient*>(c);
    const unsigned long request = umockdev_ioctl_client_get_request(client);
    UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
    std::lock_guard lock(mutex_);
    int result = ENOTTY;
    UMockdevIoctlData* resolved = nullptr;
    const bool reaping = request == USBDEVFS_REAPURB || request == USBDEVFS_REAPURBNDELAY;
    if (unplugged_ && !reaping && request != USBDEVFS_DISCARDURB &&
        request != USBDEVFS_RELEASEINTERFACE) {
        result = ENODEV;
    } else if (request == USBDEVFS_GET_CAPABILITIES) {
        GError* error = nullptr;
        UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(std::uint32_t), &error);
        const std::uint32_t caps = USBDEVFS_CAP_BULK_CONTINUATION |
                                   USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
                                   USBDEVFS_CAP_REAP_AFTER_DISCONNECT | USBDEVFS_CAP_ZERO_PACKET;
        std::memcpy(d->data, &caps, sizeof(caps));
        result = 0;
        resolved = d;
    } else if (request == USBDEVFS_GETDRIVER || request == USBDEVFS_IOCTL) {
        result = ENODATA;  // no kernel driver bound
    } else if (request == USBDEVFS_CLAIMINTERFACE || request == USBDEVFS_RELEASEINTERFACE ||
               request == USBDEVFS_CLEAR_HALT || request == USBDEVFS_RESETEP ||
               request == USBDEVFS_SETCONFIGURATION) {
        result = 0;
    } else if (request == USBDEVFS_SUBMITURB) {
        result = submit(arg);
    } else if (reaping) {
        GError* error = nullptr;
        UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(void*), &error);
        result = d == nullptr ? EFAULT : reap(d);
        resolved = d;
    } else if (request == USBDEVFS_DISCARDURB) {
        result = discard(*reinterpret_cast<unsigned long*>(arg->data));
    }
    umockdev_ioctl_client_complete(client, result == 0 ? 0 : -1, result);
    if (resolved) g_object_unref(resolved);
    return true;
}

}  // namespace anascan::drivers::test
