#include "anascan/drivers/usb_devices.hpp"

#include <algorithm>
#include <atomic>
#include <thread>

#include "anascan/drivers/usb_bulk_camera.hpp"
#include "libusb_handles.hpp"

namespace anascan::drivers {

std::span<const SupportedUsbDevice> supported_usb_devices() {
    static const SupportedUsbDevice kTable[] = {
        {0x1209, 0x0001, "bulk-frame depth camera (pid.codes test ID)", DeviceKind::kTimeOfFlight,
         StreamProfile{32, 24, PixelFormat::kZ16, 0.0}},
    };
    return kTable;
}

const SupportedUsbDevice* find_supported_usb_device(std::uint16_t vendor_id,
                                                    std::uint16_t product_id) {
    for (const SupportedUsbDevice& d : supported_usb_devices())
        if (d.vendor_id == vendor_id && d.product_id == product_id) return &d;
    return nullptr;
}

namespace {

std::optional<DeviceInfo> info_of(libusb_device* device) {
    libusb_device_descriptor desc{};
    if (libusb_get_device_descriptor(device, &desc) != 0) return std::nullopt;
    const SupportedUsbDevice* row = find_supported_usb_device(desc.idVendor, desc.idProduct);
    if (row == nullptr) return std::nullopt;
    return DeviceInfo{.uri = usb_uri(desc.idVendor, desc.idProduct),
                      .model = row->model,
                      .serial = "bus " + std::to_string(libusb_get_bus_number(device)) +
                                " address " + std::to_string(libusb_get_device_address(device)),
                      .kind = row->kind,
                      .is_camera = true};
}

}  // namespace

std::vector<DeviceInfo> enumerate_usb_devices() {
    auto context = make_libusb_context();
    if (!context) return {};
    libusb_device** raw = nullptr;
    const ssize_t n = libusb_get_device_list(context->get(), &raw);
    if (n < 0) return {};
    LibusbDeviceList list(raw);
    std::vector<DeviceInfo> found;
    for (ssize_t i = 0; i < n; ++i)
        if (auto info = info_of(list[i])) found.push_back(*info);
    return found;
}

namespace {

/// libusb hotplug: callbacks run on the event thread this class owns.
class LibusbHotplugWatcher final : public UsbHotplugWatcher {
public:
    LibusbHotplugWatcher(LibusbContext context, std::function<void(const DeviceEvent&)> on_event)
        : context_(std::move(context)), on_event_(std::move(on_event)) {}
    ~LibusbHotplugWatcher() override {
        stop_ = true;
        libusb_hotplug_deregister_callback(context_.get(), handle_);  // wakes the event loop
        if (thread_.joinable()) thread_.join();
    }
    Expected<void> start() {
        const int r = libusb_hotplug_register_callback(
            context_.get(),
            static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED |
                                              LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
            LIBUSB_HOTPLUG_ENUMERATE, LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY,
            LIBUSB_HOTPLUG_MATCH_ANY, &LibusbHotplugWatcher::callback, this, &handle_);
        if (r != LIBUSB_SUCCESS) return fail(libusb_error("usb", "hotplug registration", r));
        thread_ = std::thread([this] {
            timeval tv{0, 100000};
            while (!stop_) libusb_handle_events_timeout_completed(context_.get(), &tv, nullptr);
        });
        return {};
    }
    bool uses_libusb_hotplug() const override { return true; }

private:
    static int callback(libusb_context*, libusb_device* device, libusb_hotplug_event event,
                        void* self) {
        auto* watcher = static_cast<LibusbHotplugWatcher*>(self);
        if (auto info = info_of(device)) {
            const auto type = event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED
                                  ? DeviceEventType::kArrived
                                  : DeviceEventType::kRemoved;
            watcher->on_event_({type, *info});
        }
        return 0;  // stay registered
    }

    LibusbContext context_;
    std::function<void(const DeviceEvent&)> on_event_;
    libusb_hotplug_callback_handle handle_ = 0;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

/// Polling fallback: a registry holding only the usb backend, watched.
class PollingUsbWatcher final : public UsbHotplugWatcher {
public:
    PollingUsbWatcher(std::function<void(const DeviceEvent&)> on_event,
                      std::chrono::milliseconds period) {
        (void)registry_.add(make_usb_backend());
        watcher_ = std::make_unique<DeviceWatcher>(registry_, std::move(on_event), period);
    }
    bool uses_libusb_hotplug() const override { return false; }

private:
    DeviceRegistry registry_;
    std::unique_ptr<DeviceWatcher> watcher_;
};

}  // namespace

Expected<std::unique_ptr<UsbHotplugWatcher>> UsbHotplugWatcher::start(
    std::function<void(const DeviceEvent&)> on_event, std::chrono::milliseconds poll_period) {
    if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) {
        auto context = make_libusb_context();
        if (context) {
            auto watcher = std::make_unique<LibusbHotplugWatcher>(std::move(*context), on_event);
            if (watcher->start()) return std::unique_ptr<UsbHotplugWatcher>(std::move(watcher));
        }
    }
    return std::unique_ptr<UsbHotplugWatcher>(
        new PollingUsbWatcher(std::move(on_event), poll_period));
}

Backend make_usb_backend() {
    return Backend{
        .scheme = "usb",
        .description = "supported USB devices by VID:PID, e.g. usb:1209:0001",
        .enumerate = [] { return enumerate_usb_devices(); },
        .open = [](const DeviceUri& uri) -> Expected<std::unique_ptr<Device>> {
            const auto vid =
                static_cast<std::uint16_t>(std::stoul(uri.target.substr(0, 4), nullptr, 16));
            const auto pid =
                static_cast<std::uint16_t>(std::stoul(uri.target.substr(5, 4), nullptr, 16));
            const SupportedUsbDevice* row = find_supported_usb_device(vid, pid);
            if (row == nullptr) {
                return fail(ErrorCode::kUnsupported,
                            to_string(uri) + ": not in the table of supported USB devices");
            }
            auto transport = open_libusb_transport(vid, pid);
            if (!transport) return fail(transport.error());
            return std::unique_ptr<Device>(open_usb_bulk_camera(std::move(*transport), *row));
        }};
}

}  // namespace anascan::drivers
