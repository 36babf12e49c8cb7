#pragma once
/// \file
/// Recording of a device to a folder, as a decorator around any Camera or Scanner, and its
/// playback as a device of the same kind (`playback:/path/to/folder`). Format
/// (docs/devices.md):
///   device.json  - format name and version, device info, settings, capabilities,
///                  calibration; written to a temporary file, fsynced, then renamed.
///   frames.bin   - appended records: a 56-byte little-endian header (magic "ANFR",
///                  version, pixel format, width, height, stride, sequence, timestamp,
///                  payload size, CRC-32 of the payload) and the payload. A crash can
///                  only leave a partial last record, which playback ignores.
///   scans/NNNNNN.ply, scans/NNNNNN.json - a scanner's scans: binary PLY, then the
///                  metadata (pose, sensor origin, settings), each written crash-safely;
///                  the .json is written last and marks the scan as complete.

#include <filesystem>
#include <memory>

#include "anascan/drivers/camera.hpp"
#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/scanner.hpp"

namespace anascan::drivers {

struct RecordingConfig {
    std::filesystem::path folder;  ///< Created if missing; must not hold a recording yet.
    int fsync_every_frames = 30;   ///< Frames are durable at least this often (and at stop).
};

/// Wraps `camera`: behaves exactly like it and appends every frame it delivers to the
/// recording. Not thread-safe (like every Camera). Write failures end the stream with kIo.
Expected<std::unique_ptr<Camera>> record_camera(std::unique_ptr<Camera> camera,
                                                const RecordingConfig& config);

struct PlaybackConfig {
    std::filesystem::path folder;
    bool loop = false;  ///< Start again at the end instead of ending with kEmpty.
};

/// A recorded stream as a camera: same info (uri `playback:<folder>`), settings,
/// calibration and frames in order. At the end: kEmpty ("end of recording"). A corrupt
/// frame (CRC mismatch) or a partial last record ends the recording there.
Expected<std::unique_ptr<Camera>> open_playback(const PlaybackConfig& config);

/// Wraps `scanner`: behaves like it and writes every scan it captures (a write failure is
/// returned as kIo instead of the scan). Not thread-safe (like every Scanner).
Expected<std::unique_ptr<Scanner>> record_scanner(std::unique_ptr<Scanner> scanner,
                                                  const RecordingConfig& config);

/// A recorded scanner: capture_scan() returns the complete recorded scans in order, with
/// their metadata, then kEmpty.
Expected<std::unique_ptr<Scanner>> open_scan_playback(const PlaybackConfig& config);

/// The camera or scanner recording the folder holds.
Expected<std::unique_ptr<Device>> open_playback_device(const PlaybackConfig& config);

/// The `playback:` backend (nothing to enumerate: recordings are folders).
Backend make_playback_backend();

}  // namespace anascan::drivers
