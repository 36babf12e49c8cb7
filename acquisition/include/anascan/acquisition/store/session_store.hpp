#pragma once
/// \file
/// The session store: one folder per capture session. `DIR/session.sqlite` (SQLite, WAL,
/// synchronous=FULL) holds devices, the ordered scan list, events, notes and key/value
/// JSON; `DIR/scans/scan_NNNNNN.ply` holds each scan's points (binary little-endian PLY).
///
/// Write order of a scan (see docs/session-store.md): temp file, fsync, rename, fsync the
/// folder, then INSERT + COMMIT. `save_scan` returns only after the commit: that is the
/// acknowledgement. A crash between rename and commit leaves a final file without a row,
/// which is NOT acknowledged; `check_session` moves it to `DIR/recovered/`.

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/core/scan.hpp"

namespace anascan::acquisition {

/// kFlagged: registered, then taken out of its group because it contradicts the group's
/// other scans (the reason is in its quality JSON and a "registration-flagged" event).
enum class ScanState { kQueued, kRegistered, kFailed, kExcluded, kFlagged };

/// "queued" "registered" "failed" "excluded" "flagged".
std::string_view to_string(ScanState state);
/// Inverse of to_string; nullopt for an unknown name.
std::optional<ScanState> parse_scan_state(std::string_view name);

using TimePoint = std::chrono::system_clock::time_point;

struct ScanRecord {
    std::int64_t seq = 0;  ///< 1, 2, 3 ... in acknowledgement order.
    std::string file;      ///< Relative to the session folder: "scans/scan_000001.ply".
    std::string device_id;
    DeviceKind device_kind = DeviceKind::kUnknown;
    TimePoint captured_at{}, acknowledged_at{};
    std::string settings_json;
    std::optional<Eigen::Vector3d> sensor_origin_scan_m;
    std::optional<Pose> pose_prior;  ///< T_world_scan prior from the device, if any.
    std::optional<Pose> true_pose;   ///< Simulated ground truth (T_world_scan), if known.
    std::size_t point_count = 0;
    ScanState state = ScanState::kQueued;  ///< kExcluded while `excluded` is set.
    bool excluded = false;                 ///< Operator exclusion (undoable).
    int group = -1;
    std::optional<Pose> pose;         ///< Registered T_world_scan (world = frame of its group).
    std::string quality_json;         ///< The registrar's figures (JSON object text).
    std::optional<double> latency_s;  ///< Acknowledgement -> registered, seconds.
    bool turned_over_before = false;  ///< The operator turned the stone over before this scan.
    std::string file_problem;         ///< Set by `session check --repair` (file damaged).
    /// CRC-32 (zlib) of the file's bytes at acknowledgement; empty for scans saved by an
    /// anascan older than schema 3 until `session check --repair` records it.
    std::optional<std::uint32_t> file_crc32;
};

/// What the registration worker decided for one scan.
struct RegistrationUpdate {
    ScanState state = ScanState::kRegistered;
    int group = -1;
    std::optional<Pose> pose;
    std::string quality_json;
    std::optional<double> latency_s;
};

/// A pose in a group's frame (background refinement, group merges).
struct PoseInGroup {
    int group = -1;
    Pose T_group_scan = Pose::Identity();
};

enum class SessionOpenMode {
    kCreateOrOpen,  ///< Creates the folder and database when absent.
    kOpenExisting,  ///< The database must exist.
    kReadOnly,      ///< Must exist; no writes (info, export).
    /// Must exist; small edits (exclusion, notes, marks, registration results) alongside
    /// a running capture that holds the writer lock; cannot save scans.
    kEdit,
};

struct EventRecord {
    std::int64_t id = 0;
    TimePoint time{};
    std::string kind, device, message;
};

struct SessionNote {
    std::int64_t id = 0;
    TimePoint time{};
    std::optional<std::int64_t> seq;  ///< The scan the note is about, if any.
    std::string text;
};

struct DeviceRecord {
    std::string id;
    DeviceKind kind = DeviceKind::kUnknown;
    TimePoint first_seen{};
};

/// Current database schema version (`PRAGMA user_version`).
inline constexpr int kSessionSchemaVersion = 3;

/// "scans/scan_000042.ply".
std::string scan_file_name(std::int64_t seq);

/// Thread-safe: one mutex around one SQLite connection; saves are serialised among
/// themselves by a second mutex so that writing a PLY never blocks the database. A store
/// opened with kCreateOrOpen or kOpenExisting holds an exclusive lock on `DIR/session.lock`
/// (another such open gets kBusy): only it saves scans and repairs.
class SessionStore {
public:
    static Expected<std::unique_ptr<SessionStore>> open(const std::filesystem::path& dir,
                                                        SessionOpenMode mode);
    ~SessionStore();
    SessionStore(const SessionStore&) = delete;
    SessionStore& operator=(const SessionStore&) = delete;

    /// Writes the scan (crash-safe PLY), then inserts its row and commits. Returns only when
    /// both are durable: the acknowledgement. `scan.meta.T_world_scan` is the pose prior.
    /// On error nothing is recorded and no final file remains; the message names the file
    /// and says what to do.
    Expected<ScanRecord> save_scan(const Scan& scan, const std::optional<Pose>& true_pose);
    Expected<void> record_registration(std::int64_t seq, const RegistrationUpdate& update);
    /// Background refinement / group merge: all in one transaction.
    Expected<void> update_poses(const std::vector<std::pair<std::int64_t, PoseInGroup>>& poses);
    Expected<void> set_excluded(std::int64_t seq, bool excluded);
    Expected<void> add_event(std::string_view kind, std::string_view device,
                             std::string_view message);
    Expected<void> add_note(std::optional<std::int64_t> seq, std::string_view text);
    /// Records that the stone was turned over after scan `after_seq` (an event + the flag
    /// `turned_over_before` of scan after_seq + 1).
    Expected<void> mark_turned_over(std::int64_t after_seq);
    /// Marks a scan whose file is damaged: state failed, `file_problem` set, an event.
    Expected<void> mark_file_problem(std::int64_t seq, std::string_view problem);
    /// Records the CRC-32 of a scan saved without one (an older session, after its file was
    /// checked intact).
    Expected<void> record_file_crc32(std::int64_t seq, std::uint32_t crc32);

    Expected<std::vector<ScanRecord>> scans() const;  ///< In sequence order.
    Expected<ScanRecord> scan(std::int64_t seq) const;
    /// Reads the PLY (checking its recorded CRC-32 and point count), fills meta.
    Expected<Scan> load_scan(std::int64_t seq) const;
    Expected<std::vector<EventRecord>> events() const;
    Expected<std::vector<SessionNote>> notes() const;
    Expected<std::vector<DeviceRecord>> devices() const;
    Expected<void> set_value(std::string_view key, std::string_view json);
    Expected<std::optional<std::string>> value(std::string_view key) const;
    /// `PRAGMA integrity_check`: "ok" or SQLite's list of problems.
    Expected<std::string> integrity_check() const;
    /// Folds the WAL into the database file (after recovery).
    Expected<void> checkpoint();

    const std::filesystem::path& dir() const;
    bool read_only() const;

    struct Impl;

private:
    explicit SessionStore(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace anascan::acquisition
