#pragma once
/// \file
/// The device model (after librealsense): a Device is found by enumeration, opened by URI,
/// configured with validated settings, then used as a Camera (streaming frames) or a
/// Scanner (one-shot capture_scan), and closed. Errors are values classified by how the
/// caller reacts: kDisconnected (reconnect), kTimeout (retry), kBusy (wait or pick another
/// device), kInvalidArgument (fix the setting), kIo (report), kCancelled (caller stopped).

#include <string>

#include "anascan/drivers/settings.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/scan.hpp"

namespace anascan::drivers {

class Camera;
class Scanner;

/// What a device is, as enumeration reports it (before or after opening).
struct DeviceInfo {
    std::string uri;     ///< Opens the device: "v4l2:/dev/video2", "usb:1d6b:0104", ...
    std::string model;   ///< Human-readable model ("UVC Camera", "Riegl LMS-Z420i").
    std::string serial;  ///< Serial number or bus address; may be empty.
    DeviceKind kind = DeviceKind::kUnknown;  ///< What its scans are (structured light, ToF).
    bool is_camera = false;                  ///< Opens as a Camera (streams frames).
    bool is_scanner = false;                 ///< Opens as a Scanner (captures scans).
    friend bool operator==(const DeviceInfo&, const DeviceInfo&) = default;
};

/// An open device. Not thread-safe: one thread configures and closes it. A Camera's frames
/// are produced on one capture thread (see stream_runner.hpp); close() after stopping it.
/// Every OS handle is owned by an RAII member, so destroying a device releases all.
class Device {
public:
    virtual ~Device() = default;
    Device() = default;
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    virtual const DeviceInfo& info() const = 0;
    virtual const Capabilities& capabilities() const = 0;
    /// The settings in effect (every field the device has is present).
    virtual DeviceSettings settings() const = 0;
    /// Validates then applies the present fields; on error nothing changes.
    virtual Expected<void> configure(const DeviceSettings& requested) = 0;
    /// Calibration as JSON text (intrinsics, depth unit, ...); "{}" when none.
    virtual std::string calibration_json() const { return "{}"; }
    /// Releases the OS handles; idempotent. Later calls fail with kDisconnected.
    virtual void close() = 0;

    virtual Camera* as_camera() { return nullptr; }
    virtual Scanner* as_scanner() { return nullptr; }
};

}  // namespace anascan::drivers
