#pragma once
// Between the drivers' typed settings and acquisition's DeviceSettingsForm (device_control.hpp).

#include <chrono>
#include <vector>

#include "anascan/acquisition/capture/device_control.hpp"
#include "anascan/drivers/device.hpp"
#include "anascan/drivers/frame.hpp"
#include "anascan/processing/core/expected.hpp"

namespace anascan::acquisition {

/// Every setting `device` has (its capabilities), with the values in effect.
DeviceSettingsForm settings_form(const drivers::Device& device);

/// The form's values as the drivers' settings: kInvalidArgument naming the device and the
/// setting for a key the device does not have, a choice out of range or a value that is
/// not a finite number. Ranges are checked by the device's configure().
Expected<drivers::DeviceSettings> form_settings(const DeviceSettingsForm& form,
                                                const drivers::Capabilities& caps);

/// Grey frames → a preview, each downscaled to at most `max_width_px` wide (kFormat naming
/// the device for a frame that is not grey8 or is short).
Expected<CameraPreview> camera_preview(const drivers::DeviceInfo& info,
                                       const std::vector<drivers::Frame>& frames, int max_width_px);

}  // namespace anascan::acquisition
