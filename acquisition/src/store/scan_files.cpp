// SessionStore: writing a scan (file first, then its row) and reading it back.
#include <zlib.h>

#include <algorithm>
#include <cstdio>

#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"
#include "store/codec.hpp"
#include "store/impl.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

bool contains(std::string_view text, std::string_view part) {
    return text.find(part) != std::string_view::npos;
}

std::string advice(std::string_view message) {
    if (contains(message, "No space left") || contains(message, "File too large") ||
        contains(message, "disk is full")) {
        return " The disk is full: free space (or choose another session folder) and retry.";
    }
    if (contains(message, "Read-only") || contains(message, "Permission denied") ||
        contains(message, "Not a directory") || contains(message, "readonly")) {
        return " The session folder is not writable: fix its permissions or choose another "
               "folder.";
    }
    return "";
}

Error save_error(const fs::path& dir, std::int64_t seq, const Error& cause) {
    return Error{cause.code, "cannot save scan " + std::to_string(seq) + " in session " +
                                 dir.string() + ": " + cause.message +
                                 ". Nothing was recorded for this scan; scans saved before are "
                                 "safe." +
                                 advice(cause.message)};
}

io::PlyWriteOptions ply_options(std::int64_t seq, const Scan& scan) {
    io::PlyWriteOptions options{.format = io::PlyFormat::kBinaryLittleEndian, .comments = {}};
    options.comments.push_back("anascan session scan " + std::to_string(seq));
    if (!scan.meta.device_id.empty())
        options.comments.push_back("anascan device " + scan.meta.device_id);
    if (const auto origin = codec::vector_to_text(scan.meta.sensor_origin_scan_m))
        options.comments.push_back("anascan sensor_origin_m " + *origin);
    return options;
}

Expected<std::int64_t> next_seq(const db::Connection& db) {
    auto stmt = db::Statement::prepare(db, "SELECT COALESCE(MAX(seq), 0) + 1 FROM scans");
    if (!stmt) return fail(stmt.error());
    auto row = stmt->step("cannot read the scan list");
    if (!row) return fail(row.error());
    return stmt->int64(0);
}

Expected<void> insert_row(db::Connection& db, const ScanRecord& r) {
    auto tx = db::Transaction::begin(db);
    if (!tx) return fail(tx.error());
    auto device = db::Statement::prepare(
        db, "INSERT OR IGNORE INTO devices(id, kind, first_seen_ns) VALUES(?,?,?)");
    if (!device) return fail(device.error());
    device->bind(1, r.device_id)
        .bind(2, std::string_view(to_string(r.device_kind)))
        .bind(3, codec::to_ns(r.acknowledged_at));
    if (auto ok = device->run("cannot record the device"); !ok) return ok;
    auto stmt = db::Statement::prepare(
        db,
        "INSERT INTO scans(seq, file, device_id, device_kind, captured_ns, acknowledged_ns, "
        "settings_json, sensor_origin_m, pose_prior, true_pose, point_count, state, "
        "file_crc32) VALUES(?,?,?,?,?,?,?,?,?,?,?,'queued',?)");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, r.seq)
        .bind(2, r.file)
        .bind(3, r.device_id)
        .bind(4, std::string_view(to_string(r.device_kind)))
        .bind(5, codec::to_ns(r.captured_at))
        .bind(6, codec::to_ns(r.acknowledged_at))
        .bind(7, r.settings_json)
        .bind(8, codec::vector_to_text(r.sensor_origin_scan_m))
        .bind(9, codec::pose_to_text(r.pose_prior))
        .bind(10, codec::pose_to_text(r.true_pose))
        .bind(11, static_cast<std::int64_t>(r.point_count))
        .bind(12, r.file_crc32 ? std::optional<std::int64_t>(*r.file_crc32) : std::nullopt);
    if (auto ok = stmt->run("cannot record the scan"); !ok) return ok;
    return tx->commit();
}

ScanRecord record_of(std::int64_t seq, const Scan& scan, const std::optional<Pose>& true_pose) {
    ScanRecord r;
    r.seq = seq;
    r.file = scan_file_name(seq);
    r.device_id = scan.meta.device_id;
    r.device_kind = scan.meta.device_kind;
    r.captured_at =
        scan.meta.time == TimePoint{} ? std::chrono::system_clock::now() : scan.meta.time;
    r.settings_json = scan.meta.settings_json;
    r.sensor_origin_scan_m = scan.meta.sensor_origin_scan_m;
    r.pose_prior = scan.meta.T_world_scan;
    r.true_pose = true_pose;
    r.point_count = scan.cloud.size();
    return r;
}

}  // namespace

std::uint32_t file_crc32(std::span<const char> bytes) {
    uLong crc = crc32(0L, Z_NULL, 0);
    // zlib takes at most 4 GiB - 1 per call.
    constexpr std::size_t kChunk = std::size_t{1} << 30;
    for (std::size_t at = 0; at < bytes.size(); at += kChunk) {
        const std::size_t n = std::min(kChunk, bytes.size() - at);
        crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), static_cast<uInt>(n));
    }
    return static_cast<std::uint32_t>(crc);
}

std::string crc_mismatch(std::uint32_t found, std::uint32_t recorded) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "its CRC-32 is %08x, the session recorded %08x at acknowledgement (the file "
                  "changed since: a torn write or flipped bits)",
                  found, recorded);
    return text;
}

Expected<fs::path> move_to_recovered(const fs::path& dir, const std::string& file) {
    std::error_code ec;
    fs::create_directories(dir / "recovered", ec);
    const fs::path name = fs::path(file).filename();
    fs::path target = dir / "recovered" / name;
    for (int i = 1; fs::exists(target, ec); ++i) {
        target = dir / "recovered" /
                 (name.stem().string() + "." + std::to_string(i) + name.extension().string());
    }
    fs::rename(dir / file, target, ec);
    if (ec) {
        return fail(session_error(dir / file, ErrorCode::kIo,
                                  "cannot move to " + target.string() + ": " + ec.message()));
    }
    return target;
}

Expected<ScanRecord> SessionStore::save_scan(const Scan& scan,
                                             const std::optional<Pose>& true_pose) {
    if (impl_->read_only) return fail(read_only_error(impl_->dir));
    if (impl_->lock_fd < 0) {
        return fail(session_error(impl_->dir, ErrorCode::kInvalidArgument,
                                  "opened for edits only: scans are saved by the writer"));
    }
    if (!scan.cloud.attributes_consistent()) {
        return fail(session_error(impl_->dir, ErrorCode::kInvalidArgument,
                                  "cannot save a scan: " + describe_inconsistency(scan.cloud)));
    }
    std::lock_guard save_lock(impl_->save_mutex);
    Expected<std::int64_t> seq = 0;
    {
        std::lock_guard lock(impl_->mutex);
        seq = next_seq(impl_->db);
    }
    if (!seq) return fail(save_error(impl_->dir, 0, seq.error()));
    ScanRecord record = record_of(*seq, scan, true_pose);
    const fs::path path = impl_->dir / record.file;
    // A final file without a row is a save interrupted between rename and commit: never
    // acknowledged. Keep it aside rather than overwrite it.
    std::error_code ec;
    if (fs::exists(path, ec)) {
        if (auto moved = move_to_recovered(impl_->dir, record.file); !moved) {
            return fail(save_error(impl_->dir, *seq, moved.error()));
        }
    }
    const std::vector<char> bytes = io::serialize_ply(scan.cloud, {}, ply_options(*seq, scan));
    record.file_crc32 = file_crc32(bytes);
    if (auto ok = io::write_file_atomically(path, bytes); !ok) {
        return fail(save_error(impl_->dir, *seq, ok.error()));
    }
    std::lock_guard lock(impl_->mutex);
    record.acknowledged_at = std::chrono::system_clock::now();
    if (auto ok = insert_row(impl_->db, record); !ok) {
        std::error_code ignored;
        fs::remove(path, ignored);  // No row, so no final file either.
        return fail(save_error(impl_->dir, *seq, ok.error()));
    }
    return record;
}

Expected<Scan> SessionStore::load_scan(std::int64_t seq) const {
    auto record = scan(seq);
    if (!record) return fail(record.error());
    const fs::path path = impl_->dir / record->file;
    auto bytes = io::read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    if (const std::uint32_t crc = file_crc32(*bytes);
        record->file_crc32 && crc != *record->file_crc32) {
        return fail(ErrorCode::kFormat,
                    path.string() + ": " + crc_mismatch(crc, *record->file_crc32) +
                        " (run `anascan session check " + impl_->dir.string() + "`)");
    }
    auto ply = io::parse_ply(*bytes, path.string());
    if (!ply) return fail(ply.error());
    if (ply->cloud.size() != record->point_count) {
        return fail(ErrorCode::kTruncated,
                    (impl_->dir / record->file).string() + ": holds " +
                        std::to_string(ply->cloud.size()) + " points, the session recorded " +
                        std::to_string(record->point_count) + " (run `anascan session check " +
                        impl_->dir.string() + "`)");
    }
    Scan scan;
    scan.cloud = std::move(ply->cloud);
    scan.meta.id = fs::path(record->file).stem().string();
    scan.meta.sequence = record->seq;
    scan.meta.device_id = record->device_id;
    scan.meta.device_kind = record->device_kind;
    scan.meta.sensor_origin_scan_m = record->sensor_origin_scan_m;
    scan.meta.T_world_scan = record->pose ? record->pose : record->pose_prior;
    scan.meta.time = record->captured_at;
    scan.meta.settings_json = record->settings_json;
    return scan;
}

}  // namespace anascan::acquisition
