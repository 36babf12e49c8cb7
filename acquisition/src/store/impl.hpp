#pragma once
// The state behind SessionStore (shared by the session_store*.cpp files).
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <span>
#include <string>

#include "anascan/acquisition/store/session_store.hpp"
#include "store/db.hpp"

namespace anascan::acquisition {

struct SessionStore::Impl {
    std::filesystem::path dir;
    bool read_only = false;
    mutable std::mutex mutex;  ///< Around `db`.
    std::mutex save_mutex;     ///< Serialises save_scan (seq allocation + file + row).
    db::Connection db;
    int lock_fd = -1;  ///< flock'ed DIR/session.lock of a writable store.
    ~Impl();
};

/// Error for a write attempted on a read-only store.
Error read_only_error(const std::filesystem::path& dir);

/// Column list and reader of a `scans` row (+ whether a turnover precedes it).
extern const char* const kScanColumns;
ScanRecord read_scan_row(const db::Statement& row);

/// Moves `DIR/file` (relative) to `DIR/recovered/` under a free name; returns the new path.
Expected<std::filesystem::path> move_to_recovered(const std::filesystem::path& dir,
                                                  const std::string& file);

/// CRC-32 (zlib) of a scan file's bytes, as recorded at acknowledgement.
std::uint32_t file_crc32(std::span<const char> bytes);
/// "its CRC-32 is ..., the session recorded ...": the problem of a changed file.
std::string crc_mismatch(std::uint32_t found, std::uint32_t recorded);

/// "DIR: what: the message" for errors not coming from SQLite.
Error session_error(const std::filesystem::path& dir, ErrorCode code, std::string_view message);

}  // namespace anascan::acquisition
