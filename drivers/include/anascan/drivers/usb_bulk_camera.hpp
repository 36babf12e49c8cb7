#pragma once
/// \file
/// A camera on the bulk-frame USB protocol, over any UsbTransport:
///   control OUT, vendor request 0x01 (value 1 = start, 0 = stop streaming);
///   control OUT, vendor request 0x02 (value = exposure in 100 µs units);
///   bulk IN endpoint 0x81: one transfer per frame, a 16-byte header (magic "AFRM",
///   u16 width, u16 height, u8 pixel format (PixelFormat), 3 reserved, u32 sequence,
///   little-endian) followed by the pixels.

#include <memory>

#include "anascan/drivers/camera.hpp"
#include "anascan/drivers/usb_devices.hpp"
#include "anascan/drivers/usb_transport.hpp"

namespace anascan::drivers {

namespace usb_bulk {
inline constexpr std::uint8_t kRequestStreaming = 0x01;
inline constexpr std::uint8_t kRequestExposure = 0x02;
inline constexpr std::uint8_t kFrameEndpoint = 0x81;
inline constexpr std::size_t kHeaderBytes = 16;
}  // namespace usb_bulk

/// The camera owns the transport. Not thread-safe (see Camera).
std::unique_ptr<Camera> open_usb_bulk_camera(std::unique_ptr<UsbTransport> transport,
                                             const SupportedUsbDevice& model);

}  // namespace anascan::drivers
