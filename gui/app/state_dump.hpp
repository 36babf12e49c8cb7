#pragma once
/// \file
/// `--dump-state FILE.json`: the field app's view state as JSON, so that a test can compare
/// what the app shows with `anascan session info --json` and `anascan coverage --json`.

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>

#include "anascan/gui/assembly_view.hpp"
#include "anascan/gui/field_view_state.hpp"
#include "anascan/processing/core/expected.hpp"

namespace anascan::field {

/// What the 3D view holds besides the state.
struct ViewFigures {
    std::size_t points_total = 0;  ///< Points of the chunks in the renderer.
    std::size_t chunks = 0;
    /// Where the camera preview was drawn in the last frame: x, y, width, height in window
    /// pixels (top left origin); absent when it was not drawn.
    std::optional<std::array<float, 4>> camera_preview_rect;
    std::size_t mesh_triangles = 0;  ///< Triangles of the mesh on the GPU.
};

/// {"session", "session_check", "scans": [{"seq", "device_id", "state" (queued|registered|
/// failed|excluded), "group", "rms_mm" | null, "overlap_percent" | null, "message"}],
/// "coverage_percent" | null, "coverage_fraction" | null, "queued_registrations",
/// "disk_free_bytes" | null, "last_error", "banner" | null, "devices": [{"id", "kind",
/// "connected", "status"}], "active_device", "points_total", "chunks"}.
Expected<void> write_state_json(const std::filesystem::path& file, const gui::FieldViewState& view,
                                const ViewFigures& figures);

/// What the assembly view holds besides its state.
struct AssemblyFigures {
    std::size_t points_total = 0;  ///< Points of the blocks in the renderer.
    std::size_t busy_frames = 0;   ///< Frames drawn while a worker ran.
    double busy_frame_max_ms = 0.0;
};

/// The assembly view's `--dump-state`: {"folder", "phase", "blocks": [{"id", "fixed"}],
/// "proposal_faces", "chosen_pairs", "chosen_coplanar", "picked_face", "report": null |
/// {"status", "coplanar", "iterations", "penetration_max_mm", "pairs"}, "saved_to",
/// "last_error", "points_total", "frames_while_busy", "longest_busy_frame_ms"}.
Expected<void> write_assembly_state_json(const std::filesystem::path& file,
                                         const gui::AssemblyViewState& view,
                                         const AssemblyFigures& figures);

}  // namespace anascan::field
