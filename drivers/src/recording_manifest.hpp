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

/// Creates `folder` for a new recording: kIo when it cannot, kInvalidArgument when it
/// already holds one (device.json or frames.bin): recordings are never overwritten.
Expected<void> prepare_recording_folder(const std::filesystem::path& folder);

/// The manifest as its playback device shows it: uri `playback:<folder>`, model marked.
RecordingManifest as_played_back(RecordingManifest manifest, const std::filesystem::path& folder);

/// configure() of a playback device: only what the recorded capabilities allow.
Expected<void> configure_played_back(RecordingManifest& manifest, bool closed,
                                     const DeviceSettings& requested);

}  // namespace anascan::drivers
