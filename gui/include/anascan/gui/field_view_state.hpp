#pragma once
/// \file
/// Everything the field app's panels show, as plain data. The panels are pure functions of
/// this state (no `static` locals), so they can be drawn and tested in a headless ImGui
/// context. The app fills it from acquisition's ScanRecords and SessionEvents; each field
/// names the ScanRecord / event field it mirrors.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "anascan/acquisition/capture/device_control.hpp"

namespace anascan::gui {

/// Registration state of one scan: acquisition::ScanState, with the registered scans that
/// joined nothing apart (kUnjoined: placed in a group of their own, no other scan with it).
/// kFlagged: taken out of its group because it contradicts the group's other scans.
enum class ScanRowState { kQueued, kRegistered, kUnjoined, kFailed, kExcluded, kFlagged };

/// As the scan list shows it: "queued", "ok", "unjoined", "FAILED" (capitals: it must stand
/// out), "excluded", "CONTRADICTS".
const char* to_string(ScanRowState state);

/// One line of the scan list, in capture order.
struct ScanRow {
    std::int64_t seq = 0;                               ///< ScanRecord::seq.
    std::string device_id;                              ///< ScanRecord::device_id.
    std::chrono::system_clock::time_point captured_at;  ///< ScanRecord::captured_at.
    ScanRowState state = ScanRowState::kQueued;         ///< ScanRecord::state.
    std::optional<double> rms_mm;                       ///< Registration RMS, millimetres.
    std::optional<double> overlap_percent;              ///< Overlap with the model, 0..100 %.
    int group = -1;                                     ///< ScanRecord::group (-1: none yet).
    std::string message;  ///< The registrar's message (why it failed), may be empty.
};

/// One device of the device panel (mirrors the device list of acquisition).
struct DeviceRow {
    std::string id;    ///< Device id, e.g. "sim:tof/0".
    std::string kind;  ///< "time-of-flight", "structured-light", ...
    bool connected = false;
    std::string status;  ///< Last status line ("ready", "unplugged", ...).
};

/// The connected device's settings as the device panel edits them (acquisition's form).
struct DeviceSettingsState {
    acquisition::DeviceSettingsForm applied;  ///< In effect on the device (read or applied).
    acquisition::DeviceSettingsForm edited;   ///< As the operator typed (starts as applied).
    bool busy = false;                        ///< Reading or applying in progress.
    std::string message;                      ///< The device's answer to the last apply.
    bool message_is_error = false;
};

/// "Exposure 50000 µs is outside 1000-40000 µs" for a value outside the device's range or
/// not a number, else empty (the device checks again when applied).
std::string setting_problem(const acquisition::DeviceSetting& setting);

/// One camera of the live preview: a texture of its latest image.
struct CameraPreviewView {
    std::uintptr_t texture = 0;  ///< OpenGL texture (0: none).
    int width_px = 0, height_px = 0;
    std::string name;  ///< "cam1", "cam2".
};

/// The device panel: the devices, which one captures, whether a capture is running.
struct DevicePanelState {
    std::vector<DeviceRow> devices;
    int active_device = -1;  ///< Index into devices, -1 when none is chosen.
    bool capturing = false;  ///< A capture is in progress: the capture button is disabled.
    /// The last scan as the scanner saw it (scan_preview.hpp): an OpenGL texture (0: none).
    std::uintptr_t preview_texture = 0;
    int preview_width_px = 0, preview_height_px = 0;
    std::string preview_caption;  ///< "Scan 12 as the scanner saw it (153 204 points)".
    bool connected = false;       ///< The active device is attached to the session.
    DeviceSettingsState settings;
    /// Live camera preview (structured light: cam1, cam2), empty when none.
    std::vector<CameraPreviewView> cameras;
    std::string cameras_caption;  ///< "Cameras at 21:03:04 (0.4 s old)", or why not.
};

/// The status bar figures; an absent figure shows as "-".
struct StatusBarState {
    std::optional<double> coverage_percent;        ///< Of the stone surface, 0..100 %.
    int queued_registrations = 0;                  ///< Scans saved but not yet registered.
    std::optional<std::uint64_t> disk_free_bytes;  ///< On the session's file system.
    std::string last_error;                        ///< Last error event, empty when none.
};

/// The last capture failed (device gone, disk full, folder not writable): the banner shows
/// it until a capture succeeds.
struct CaptureProblem {
    std::string headline;     ///< A few words, large in the banner ("DISK FULL: ...").
    std::string details;      ///< acquisition's message: names the device or the folder.
    std::string what_to_try;  ///< The operator's next step.
    /// The status bar's line: headline and details.
    std::string line() const { return details.empty() ? headline : headline + ": " + details; }
};

/// How the 3D view colours the points.
enum class ColorMode { kByScan, kByQuality, kByCoverage };

/// What the 3D view draws: the scans' points, or the fragment model made from them.
enum class ViewMode { kPoints, kMesh };

/// The fragment model of the view's group (acquisition's mesh_scans, as `session export
/// --mesh` makes it), as the device panel reports it.
struct MeshViewState {
    enum class Status { kNone, kMaking, kReady, kFailed };
    Status status = Status::kNone;
    std::string message;  ///< The stage while making; the error when it failed.
    double resolution_mm = 1.0;
    int scans = 0;  ///< Scans it was made of.
    std::size_t triangles = 0;
    double area_m2 = 0.0;
    double interpolated_share = 0.0;  ///< Of the area, 0..1.
    bool closed = false;              ///< Closed 2-manifold, one component.
    double seconds = 0.0;             ///< Time the meshing took.
    /// Scans drawn in the view now that the mesh does not hold (or a moved pose): "3 newer
    /// scans"; empty when the mesh is of the scans shown.
    std::string outdated;
};

/// The whole view state of the field app.
struct FieldViewState {
    std::string session_dir;         ///< Shown in the title line; empty when no session.
    std::string session_check;       ///< `session check` findings, "new session", or empty.
    std::vector<ScanRow> scans;      ///< In capture order (ascending seq).
    std::int64_t selected_seq = -1;  ///< Highlighted scan, -1 when none.
    DevicePanelState device;
    StatusBarState status;
    std::optional<CaptureProblem> capture_problem;  ///< Until the next capture succeeds.
    ColorMode color_mode = ColorMode::kByScan;
    ViewMode view_mode = ViewMode::kPoints;  ///< kMesh only while mesh.status is kReady.
    MeshViewState mesh;
    bool high_contrast = false;
};

/// "Mesh: 812 k triangles, 0.412 m², 12.3 % interpolated, closed; 12 scans, 1.0 mm, 14.2 s",
/// "Making the mesh: normals ...", "Mesh failed: ...", or empty before the first.
std::string mesh_summary(const MeshViewState& mesh);

/// What the banner over the view reports.
enum class BannerKind {
    kCaptureFailed,  ///< The last capture failed: device gone, disk full, ... (red).
    kFailed,         ///< The newest registration outcome is a failure (red).
    kSplit,     ///< The registered scans sit in more than one group: the model is split (amber).
    kDisagree,  ///< Scans contradicted their group and were taken out of the model (red).
};

/// A failed registration or a split model, as the banner shows it: impossible to miss,
/// says what to try.
struct FailureBanner {
    BannerKind kind = BannerKind::kFailed;
    std::int64_t seq = 0;     ///< The scan the button excludes; -1: no button.
    std::string message;      ///< What happened, naming the scan(s): large.
    std::string details;      ///< More of what happened (may be empty).
    std::string what_to_try;  ///< The operator's next step.
};

/// The banner for the newest failed scan, if the newest registration outcome is a failure
/// (a later registered scan clears it: the operator has recovered).
std::optional<FailureBanner> failure_banner(const FieldViewState& state);

/// The banner for a split model: the registered, non-excluded scans sit in more than one
/// group. Names the group the view shows (the largest, as model_group chooses: most scans,
/// lowest id on a tie) and the scans outside it; `seq` is the one scan outside it when
/// there is only one (a stray scan the operator may exclude), else -1.
std::optional<FailureBanner> split_banner(const FieldViewState& state);

/// The banner for scans that contradicted their group (flagged, not excluded): names them
/// and the first one's reason; `seq` is the newest of them (the button excludes it).
std::optional<FailureBanner> disagree_banner(const FieldViewState& state);

/// The banner over the view: the capture problem, else the failure when the newest
/// registration outcome failed, else the scans that disagree, else the split warning, else
/// none.
std::optional<FailureBanner> session_banner(const FieldViewState& state);

/// "scan 4", "scans 2-12", "scans 1, 3-5, 9" (ascending seqs).
std::string format_scan_list(const std::vector<std::int64_t>& seqs);

/// The newest scan (highest seq) that is not excluded, or -1.
std::int64_t newest_scan(const FieldViewState& state);

}  // namespace anascan::gui
