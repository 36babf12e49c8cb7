#pragma once
/// \file
/// The narrow USB transport of the device layer (after librealsense): control and bulk
/// transfers with timeouts on one claimed interface. Errors: kTimeout, kDisconnected
/// (LIBUSB_ERROR_NO_DEVICE), kBusy (interface claimed elsewhere), kIo.

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

/// Not thread-safe: one thread (the device's capture thread) transfers at a time.
class UsbTransport {
public:
    virtual ~UsbTransport() = default;
    /// A control transfer; `request_type` bit 7 set = device-to-host (fills `data`).
    /// Returns the bytes transferred.
    virtual Expected<std::size_t> control_transfer(std::uint8_t request_type, std::uint8_t request,
                                                   std::uint16_t value, std::uint16_t index,
                                                   std::span<std::uint8_t> data,
                                                   std::chrono::milliseconds timeout) = 0;
    /// A bulk transfer on `endpoint` (bit 7 set = IN, fills `data`). Returns the bytes
    /// transferred.
    virtual Expected<std::size_t> bulk_transfer(std::uint8_t endpoint, std::span<std::uint8_t> data,
                                                std::chrono::milliseconds timeout) = 0;
    /// "usb:VID:PID" and bus address, for messages.
    virtual const std::string& name() const = 0;
};

/// Opens the first device with this VID:PID through libusb and claims `interface_number`
/// (kDisconnected when none is attached, kBusy when the interface is claimed).
Expected<std::unique_ptr<UsbTransport>> open_libusb_transport(std::uint16_t vendor_id,
                                                              std::uint16_t product_id,
                                                              int interface_number = 0);

}  // namespace anascan::drivers
