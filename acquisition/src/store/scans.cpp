// SessionStore: the scan rows (reading them, registration results, operator actions).
#include <cstdio>

#include "store/codec.hpp"
#include "store/impl.hpp"

namespace anascan::acquisition {
namespace {

Error no_scan(const std::filesystem::path& dir, std::int64_t seq) {
    return session_error(
        dir, ErrorCode::kInvalidArgument,
        "no scan " + std::to_string(seq) + " in this session (see `anascan session info`)");
}

// Runs an UPDATE of one scan row; an unknown seq is an error.
Expected<void> update_row(SessionStore::Impl& impl, db::Statement& stmt, std::int64_t seq,
                          std::string_view what) {
    if (auto ok = stmt.run(what); !ok) return ok;
    if (impl.db.changes() == 0) return fail(no_scan(impl.dir, seq));
    return {};
}

}  // namespace

std::string_view to_string(ScanState state) {
    switch (state) {
        case ScanState::kQueued:
            return "queued";
        case ScanState::kRegistered:
            return "registered";
        case ScanState::kFailed:
            return "failed";
        case ScanState::kExcluded:
            return "excluded";
        case ScanState::kFlagged:
            return "flagged";
    }
    return "queued";
}

std::optional<ScanState> parse_scan_state(std::string_view name) {
    for (ScanState s : {ScanState::kQueued, ScanState::kRegistered, ScanState::kFailed,
                        ScanState::kExcluded, ScanState::kFlagged}) {
        if (name == to_string(s)) return s;
    }
    return std::nullopt;
}

std::string scan_file_name(std::int64_t seq) {
    char name[48];
    std::snprintf(name, sizeof(name), "scans/scan_%06lld.ply", static_cast<long long>(seq));
    return name;
}

const char* const kScanColumns =
    "seq, file, device_id, device_kind, captured_ns, acknowledged_ns, settings_json, "
    "sensor_origin_m, pose_prior, true_pose, point_count, state, excluded, grp, pose, "
    "quality_json, latency_s, file_problem, "
    "EXISTS(SELECT 1 FROM turnovers t WHERE t.after_seq = scans.seq - 1), file_crc32";

ScanRecord read_scan_row(const db::Statement& row) {
    ScanRecord r;
    r.seq = row.int64(0);
    r.file = row.text(1);
    r.device_id = row.text(2);
    r.device_kind = codec::device_kind_from_string(row.text(3));
    r.captured_at = codec::from_ns(row.int64(4));
    r.acknowledged_at = codec::from_ns(row.int64(5));
    r.settings_json = row.text(6);
    r.sensor_origin_scan_m = codec::vector_from_text(row.text(7));
    r.pose_prior = codec::pose_from_text(row.text(8));
    r.true_pose = codec::pose_from_text(row.text(9));
    r.point_count = static_cast<std::size_t>(row.int64(10));
    r.excluded = row.int64(12) != 0;
    r.state = r.excluded ? ScanState::kExcluded
                         : parse_scan_state(row.text(11)).value_or(ScanState::kQueued);
    r.group = static_cast<int>(row.int64(13));
    r.pose = codec::pose_from_text(row.text(14));
    r.quality_json = row.text(15);
    if (!row.is_null(16)) r.latency_s = row.real(16);
    r.file_problem = row.text(17);
    r.turned_over_before = row.int64(18) != 0;
    if (!row.is_null(19)) r.file_crc32 = static_cast<std::uint32_t>(row.int64(19));
    return r;
}

Expected<std::vector<ScanRecord>> SessionStore::scans() const {
    std::lock_guard lock(impl_->mutex);
    return db::collect(impl_->db,
                       std::string("SELECT ") + kScanColumns + " FROM scans ORDER BY seq",
                       "cannot read the scan list", read_scan_row);
}

Expected<ScanRecord> SessionStore::scan(std::int64_t seq) const {
    std::lock_guard lock(impl_->mutex);
    auto stmt = db::Statement::prepare(
        impl_->db, std::string("SELECT ") + kScanColumns + " FROM scans WHERE seq = ?");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, seq);
    auto row = stmt->step("cannot read scan " + std::to_string(seq));
    if (!row) return fail(row.error());
    if (!*row) return fail(no_scan(impl_->dir, seq));
    return read_scan_row(*stmt);
}

Expected<void> SessionStore::record_registration(std::int64_t seq,
                                                 const RegistrationUpdate& update) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    if (update.state == ScanState::kExcluded) {
        return fail(session_error(impl_->dir, ErrorCode::kInvalidArgument,
                                  "exclusion is set with set_excluded, not as a registration"));
    }
    std::lock_guard lock(impl_->mutex);
    auto stmt = db::Statement::prepare(
        impl_->db,
        "UPDATE scans SET state = ?, grp = ?, pose = ?, quality_json = ?, latency_s = ? "
        "WHERE seq = ?");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, to_string(update.state))
        .bind(2, std::int64_t{update.group})
        .bind(3, codec::pose_to_text(update.pose))
        .bind(4, update.quality_json)
        .bind(5, update.latency_s)
        .bind(6, seq);
    return update_row(*impl_, *stmt, seq, "cannot record the registration");
}

Expected<void> SessionStore::update_poses(
    const std::vector<std::pair<std::int64_t, PoseInGroup>>& poses) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    std::lock_guard lock(impl_->mutex);
    auto tx = db::Transaction::begin(impl_->db);
    if (!tx) return fail(tx.error());
    for (const auto& [seq, pose] : poses) {
        auto stmt =
            db::Statement::prepare(impl_->db, "UPDATE scans SET grp = ?, pose = ? WHERE seq = ?");
        if (!stmt) return fail(stmt.error());
        stmt->bind(1, std::int64_t{pose.group})
            .bind(2, codec::pose_to_text(pose.T_group_scan))
            .bind(3, seq);
        if (auto ok = update_row(*impl_, *stmt, seq, "cannot update poses"); !ok) return ok;
    }
    return tx->commit();
}

Expected<void> SessionStore::set_excluded(std::int64_t seq, bool excluded) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    std::lock_guard lock(impl_->mutex);
    auto stmt = db::Statement::prepare(impl_->db, "UPDATE scans SET excluded = ? WHERE seq = ?");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, std::int64_t{excluded ? 1 : 0}).bind(2, seq);
    return update_row(*impl_, *stmt, seq, "cannot change the exclusion");
}

Expected<void> SessionStore::mark_turned_over(std::int64_t after_seq) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    if (after_seq < 0) {
        return fail(session_error(impl_->dir, ErrorCode::kInvalidArgument,
                                  "turned over after a negative scan number"));
    }
    {
        std::lock_guard lock(impl_->mutex);
        auto stmt = db::Statement::prepare(
            impl_->db, "INSERT OR REPLACE INTO turnovers(after_seq, time_ns) VALUES(?,?)");
        if (!stmt) return fail(stmt.error());
        stmt->bind(1, after_seq).bind(2, codec::to_ns(std::chrono::system_clock::now()));
        if (auto ok = stmt->run("cannot record the turn-over"); !ok) return ok;
    }
    return add_event("turned-over", "",
                     "stone turned over after scan " + std::to_string(after_seq));
}

Expected<void> SessionStore::mark_file_problem(std::int64_t seq, std::string_view problem) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    {
        std::lock_guard lock(impl_->mutex);
        auto stmt = db::Statement::prepare(
            impl_->db, "UPDATE scans SET state = 'failed', file_problem = ? WHERE seq = ?");
        if (!stmt) return fail(stmt.error());
        stmt->bind(1, problem).bind(2, seq);
        if (auto ok = update_row(*impl_, *stmt, seq, "cannot flag the scan"); !ok) return ok;
    }
    return add_event("scan-file-damaged", "",
                     "scan " + std::to_string(seq) + ": " + std::string(problem));
}

Expected<void> SessionStore::record_file_crc32(std::int64_t seq, std::uint32_t crc32) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    std::lock_guard lock(impl_->mutex);
    auto stmt = db::Statement::prepare(
        impl_->db, "UPDATE scans SET file_crc32 = ? WHERE seq = ? AND file_crc32 IS NULL");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, std::int64_t{crc32}).bind(2, seq);
    return stmt->run("cannot record the checksum of scan " + std::to_string(seq));
}

}  // namespace anascan::acquisition
