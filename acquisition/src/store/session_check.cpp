#include "anascan/acquisition/store/session_check.hpp"

#include <algorithm>
#include <regex>
#include <set>

#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"
#include "store/impl.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

// What is wrong with a row's file, or empty when it is fine; `crc32` gets the file's CRC-32.
std::string file_problem(const fs::path& dir, const ScanRecord& row, std::uint32_t& crc32) {
    const fs::path path = dir / row.file;
    std::error_code ec;
    if (!fs::exists(path, ec)) return "the file is missing";
    auto bytes = io::read_file_bytes(path);
    if (!bytes) return bytes.error().message;
    crc32 = file_crc32(*bytes);
    if (row.file_crc32 && crc32 != *row.file_crc32) return crc_mismatch(crc32, *row.file_crc32);
    auto ply = io::parse_ply(*bytes, path.string());
    if (!ply) return ply.error().message;
    if (ply->cloud.size() != row.point_count) {
        return "holds " + std::to_string(ply->cloud.size()) + " points, the session recorded " +
               std::to_string(row.point_count);
    }
    return {};
}

// A scan saved before checksums were recorded: --repair records the CRC-32 of its intact file.
void record_checksum(SessionStore& store, std::int64_t seq, std::uint32_t crc32, bool repair,
                     SessionCheckReport& report) {
    ++report.scans_without_checksum;
    if (!repair) return;
    if (auto ok = store.record_file_crc32(seq, crc32); ok) {
        ++report.checksums_recorded;
    } else {
        report.issues.push_back({.kind = CheckIssueKind::kDatabase,
                                 .seq = seq,
                                 .file = store.dir() / "session.sqlite",
                                 .problem = ok.error().message,
                                 .action = "could not record the checksum"});
    }
}

void check_row(SessionStore& store, const ScanRecord& row, bool repair,
               SessionCheckReport& report) {
    ++report.scans_checked;
    std::uint32_t crc32 = 0;
    const std::string problem = file_problem(store.dir(), row, crc32);
    if (problem.empty()) {
        ++report.scans_ok;
        if (!row.file_crc32) record_checksum(store, row.seq, crc32, repair, report);
        return;
    }
    CheckIssue issue{.kind = problem == "the file is missing" ? CheckIssueKind::kMissingFile
                                                              : CheckIssueKind::kDamagedFile,
                     .seq = row.seq,
                     .file = store.dir() / row.file,
                     .problem = problem};
    if (row.file_problem == problem) {
        issue.recorded = true;
        issue.action = "recorded earlier: scan marked failed (file kept)";
    } else if (repair) {
        auto ok = store.mark_file_problem(row.seq, problem);
        issue.repaired = ok.has_value();
        issue.action = ok ? "marked the scan failed with the reason (file kept)"
                          : "could not mark the scan failed: " + ok.error().message;
    } else {
        issue.action = "--repair marks the scan failed with the reason (file kept)";
    }
    report.issues.push_back(std::move(issue));
}

void check_temporary(const fs::path& path, bool repair, SessionCheckReport& report) {
    CheckIssue issue{.kind = CheckIssueKind::kTemporaryFile,
                     .file = path,
                     .problem = "temporary file of an interrupted write"};
    std::error_code ec;
    if (repair) {
        issue.repaired = fs::remove(path, ec);
        issue.action = issue.repaired ? "removed" : "could not remove: " + ec.message();
    } else {
        issue.action = "--repair removes it";
    }
    report.issues.push_back(std::move(issue));
}

void check_unacknowledged(const fs::path& dir, const std::string& file, bool repair,
                          SessionCheckReport& report) {
    CheckIssue issue{.kind = CheckIssueKind::kUnacknowledgedFile,
                     .file = dir / file,
                     .problem = "scan file without a row (written, never acknowledged)"};
    if (repair) {
        auto moved = move_to_recovered(dir, file);
        issue.repaired = moved.has_value();
        issue.action = moved ? "moved to " + moved->string() : moved.error().message;
    } else {
        issue.action = "--repair moves it to " + (dir / "recovered").string();
    }
    report.issues.push_back(std::move(issue));
}

void check_folder(const fs::path& dir, const std::set<std::string>& row_files, bool repair,
                  SessionCheckReport& report) {
    static const std::regex kFinal(R"(scan_\d+\.ply)");
    static const std::regex kTemporary(R"(\.scan_\d+\.ply\.tmp.*)");
    std::vector<fs::path> entries;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir / "scans", ec)) {
        entries.push_back(entry.path());
    }
    std::sort(entries.begin(), entries.end());
    for (const fs::path& path : entries) {
        const std::string name = path.filename().string();
        const std::string relative = "scans/" + name;
        if (std::regex_match(name, kTemporary)) {
            check_temporary(path, repair, report);
        } else if (std::regex_match(name, kFinal) && !row_files.contains(relative)) {
            check_unacknowledged(dir, relative, repair, report);
        }
    }
}

void check_database(SessionStore& store, SessionCheckReport& report) {
    auto integrity = store.integrity_check();
    report.integrity = integrity ? *integrity : integrity.error().message;
    if (report.integrity == "ok") return;
    report.issues.push_back(
        {.kind = CheckIssueKind::kDatabase,
         .file = store.dir() / "session.sqlite",
         .problem = report.integrity,
         .action = "cannot be repaired in place: copy the session folder aside, keep the scan "
                   "files and restore the database from a backup"});
}

}  // namespace

std::string_view to_string(CheckIssueKind kind) {
    switch (kind) {
        case CheckIssueKind::kMissingFile:
            return "missing-file";
        case CheckIssueKind::kDamagedFile:
            return "damaged-file";
        case CheckIssueKind::kTemporaryFile:
            return "temporary-file";
        case CheckIssueKind::kUnacknowledgedFile:
            return "unacknowledged-file";
        case CheckIssueKind::kDatabase:
            return "database";
    }
    return "database";
}

std::size_t SessionCheckReport::unresolved() const {
    return static_cast<std::size_t>(
        std::count_if(issues.begin(), issues.end(),
                      [](const CheckIssue& i) { return !i.repaired && !i.recorded; }));
}

std::vector<std::string> SessionCheckReport::lines() const {
    std::vector<std::string> out;
    out.push_back("session " + dir.string() + ": schema version " + std::to_string(schema_version) +
                  ", " + std::to_string(scans_checked) + " scans checked, " +
                  std::to_string(scans_ok) + " files ok, database integrity: " + integrity);
    for (const CheckIssue& i : issues) {
        std::string line = std::string(to_string(i.kind)) + ": " + i.file.string();
        if (i.seq) line += " (scan " + std::to_string(*i.seq) + ")";
        line += ": " + i.problem + " -> " + (i.repaired ? "repaired: " : "") + i.action;
        out.push_back(std::move(line));
    }
    if (scans_without_checksum > 0) {
        out.push_back(
            std::to_string(scans_without_checksum) + " intact scan(s) saved without a checksum: " +
            (checksums_recorded > 0 ? "recorded " + std::to_string(checksums_recorded) + " now"
                                    : std::string("--repair records them")));
    }
    const std::size_t repaired = static_cast<std::size_t>(std::count_if(
        issues.begin(), issues.end(), [](const CheckIssue& i) { return i.repaired; }));
    if (clean()) {
        out.push_back(repaired > 0
                          ? "clean after repairing " + std::to_string(repaired) + " problem(s)"
                          : "clean");
    } else {
        out.push_back(std::to_string(unresolved()) +
                      " problem(s) not repaired: run `anascan "
                      "session check " +
                      dir.string() + " --repair`");
    }
    return out;
}

Expected<SessionCheckReport> check_session(const fs::path& dir,
                                           const SessionCheckOptions& options) {
    auto store = SessionStore::open(
        dir, options.repair ? SessionOpenMode::kOpenExisting : SessionOpenMode::kReadOnly);
    if (!store) return fail(store.error());
    SessionCheckReport report;
    report.dir = dir;
    report.schema_version = kSessionSchemaVersion;
    check_database(**store, report);
    auto rows = (*store)->scans();
    if (!rows) return fail(rows.error());
    std::set<std::string> row_files;
    for (const ScanRecord& row : *rows) {
        row_files.insert(row.file);
        check_row(**store, row, options.repair, report);
    }
    check_folder(dir, row_files, options.repair, report);
    if (options.repair) {
        if (auto ok = (*store)->checkpoint(); !ok) return fail(ok.error());
        const std::size_t found = report.issues.size();
        (void)(*store)->add_event("check", "",
                                  "session check --repair: " + std::to_string(found) +
                                      " finding(s), " + std::to_string(report.unresolved()) +
                                      " unresolved");
    }
    return report;
}

}  // namespace anascan::acquisition
