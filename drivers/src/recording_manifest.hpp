#pragma once
// device.json of a recording: what was recorded, with which settings and calibration.

#include <filesystem>
#include <string>

#include "anascan/drivers/device.hpp"

namespace anascan::drivers {

struct RecordingManifest {
    DeviceInfo device;
    Capabilities capabilities;
    DeviceSettings settings;
    std::string calibration_json = "{}";
};

std::string manifest_to_json(const RecordingManifest& manifest);
/// Writes `folder`/device.json crash-safely.
Expected<void> write_manifest(const std::filesystem::path& folder,
                              const RecordingManifest& manifest);
/// Reads `folder`/device.json (kIo naming it when missing).
Expected<RecordingManifest> read_manifest(const std::filesystem::path& folder);
/// kFormat naming `path` when the text is not a version-1 anascan recording manifest.
Expected<RecordingManifest> manifest_from_json(const std::string& text,
                                               const std::filesystem::path& path);

}  // namespace anascan::drivers
