#pragma once
// RAII owners of libusb objects, and libusb error codes as our error classes.

#include <libusb.h>

#include <memory>
#include <string>

#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

struct LibusbContextDeleter {
    void operator()(libusb_context* c) const { libusb_exit(c); }
};
struct LibusbHandleDeleter {
    void operator()(libusb_device_handle* h) const { libusb_close(h); }
};
struct LibusbDeviceListDeleter {
    void operator()(libusb_device** list) const { libusb_free_device_list(list, 1); }
};
using LibusbContext = std::shared_ptr<libusb_context>;
using LibusbHandle = std::unique_ptr<libusb_device_handle, LibusbHandleDeleter>;
using LibusbDeviceList = std::unique_ptr<libusb_device*[], LibusbDeviceListDeleter>;

/// A new libusb context (kIo when libusb cannot start, e.g. no usbfs).
Expected<LibusbContext> make_libusb_context();

/// LIBUSB_ERROR_NO_DEVICE/NOT_FOUND → kDisconnected, TIMEOUT → kTimeout, BUSY → kBusy,
/// INVALID_PARAM → kInvalidArgument, else kIo; the message names the device.
Error libusb_error(const std::string& device, const std::string& what, int code);

/// "usb:vvvv:pppp" in lower-case hexadecimal.
std::string usb_uri(std::uint16_t vendor_id, std::uint16_t product_id);

}  // namespace anascan::drivers
