#include <cstdio>

#include "anascan/drivers/usb_transport.hpp"
#include "libusb_handles.hpp"

namespace anascan::drivers {

Expected<LibusbContext> make_libusb_context() {
    libusb_context* raw = nullptr;
    if (int r = libusb_init(&raw); r != 0) return fail(libusb_error("libusb", "init", r));
    return LibusbContext(raw, LibusbContextDeleter{});
}

Error libusb_error(const std::string& device, const std::string& what, int code) {
    ErrorCode c = ErrorCode::kIo;
    switch (code) {
        case LIBUSB_ERROR_NO_DEVICE:
        case LIBUSB_ERROR_NOT_FOUND:
            c = ErrorCode::kDisconnected;
            break;
        case LIBUSB_ERROR_TIMEOUT:
            c = ErrorCode::kTimeout;
            break;
        case LIBUSB_ERROR_BUSY:
            c = ErrorCode::kBusy;
            break;
        case LIBUSB_ERROR_INVALID_PARAM:
            c = ErrorCode::kInvalidArgument;
            break;
        default:
            break;
    }
    std::string message = device + ": " + what + ": " + libusb_strerror(code);
    if (code == LIBUSB_ERROR_ACCESS) message += "; is the user in the 'plugdev' group?";
    return Error{c, std::move(message)};
}

std::string usb_uri(std::uint16_t vendor_id, std::uint16_t product_id) {
    char text[16];
    std::snprintf(text, sizeof(text), "usb:%04x:%04x", vendor_id, product_id);
    return text;
}

namespace {

/// Member order is destruction order in reverse: the interface is released, then the
/// handle closed, then the context left. Not thread-safe (see UsbTransport).
class LibusbTransport final : public UsbTransport {
public:
    LibusbTransport(LibusbContext context, LibusbHandle handle, int interface_number,
                    std::string name)
        : context_(std::move(context)),
          handle_(std::move(handle)),
          interface_(interface_number),
          name_(std::move(name)) {}
    ~LibusbTransport() override { libusb_release_interface(handle_.get(), interface_); }

    Expected<std::size_t> control_transfer(std::uint8_t request_type, std::uint8_t request,
                                           std::uint16_t value, std::uint16_t index,
                                           std::span<std::uint8_t> data,
                                           std::chrono::milliseconds timeout) override {
        const int r = libusb_control_transfer(handle_.get(), request_type, request, value, index,
                                              data.data(), static_cast<std::uint16_t>(data.size()),
                                              static_cast<unsigned>(timeout.count()));
        if (r < 0) return fail(libusb_error(name_, "control transfer", r));
        return static_cast<std::size_t>(r);
    }
    Expected<std::size_t> bulk_transfer(std::uint8_t endpoint, std::span<std::uint8_t> data,
                                        std::chrono::milliseconds timeout) override {
        int transferred = 0;
        const int r = libusb_bulk_transfer(handle_.get(), endpoint, data.data(),
                                           static_cast<int>(data.size()), &transferred,
                                           static_cast<unsigned>(timeout.count()));
        if (r < 0 && !(r == LIBUSB_ERROR_TIMEOUT && transferred > 0))
            return fail(libusb_error(name_, "bulk transfer", r));
        return static_cast<std::size_t>(transferred);
    }
    const std::string& name() const override { return name_; }

private:
    LibusbContext context_;
    LibusbHandle handle_;
    int interface_;
    std::string name_;
};

}  // namespace

Expected<std::unique_ptr<UsbTransport>> open_libusb_transport(std::uint16_t vendor_id,
                                                              std::uint16_t product_id,
                                                              int interface_number) {
    const std::string name = usb_uri(vendor_id, product_id);
    auto context = make_libusb_context();
    if (!context) return fail(context.error());
    LibusbHandle handle(libusb_open_device_with_vid_pid(context->get(), vendor_id, product_id));
    if (!handle) {
        return fail(
            ErrorCode::kDisconnected,
            name + ": not attached (or no permission to open it: see 'lsusb' and udev rules)");
    }
    libusb_set_auto_detach_kernel_driver(handle.get(), 1);
    if (int r = libusb_claim_interface(handle.get(), interface_number); r != 0)
        return fail(libusb_error(name, "claim interface " + std::to_string(interface_number), r));
    return std::unique_ptr<UsbTransport>(
        new LibusbTransport(std::move(*context), std::move(handle), interface_number, name));
}

}  // namespace anascan::drivers
