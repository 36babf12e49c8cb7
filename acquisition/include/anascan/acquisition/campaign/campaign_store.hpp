#pragma once
/// \file
/// The campaign store: one folder holding an SQLite database (`campaign.sqlite`, WAL,
/// synchronous writes, a schema version) and the prepared scans (`prepared/`). It records
/// per scan the file, its prepared summary and global descriptor; the candidate pairs and
/// their results; the stones and their poses. Every result is committed as it arrives, so
/// an interrupted job resumes without redoing finished tasks. One writer at a time (a lock
/// file); readers (`campaign status`) may run alongside.
///
/// Thread safety: not thread-safe; one store per thread.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::acquisition {

/// The campaign schema this program writes (`PRAGMA user_version`).
inline constexpr int kCampaignSchemaVersion = 1;

/// One scan of the campaign as stored.
struct CampaignScanRow {
    std::int64_t id = 0;  ///< 0-based, in the order given to `init`.
    std::string file;     ///< Absolute path of the scan file.
    /// "new", "prepared", "described", or "unusable" (with `problem`).
    std::string state = "new";
    std::string problem;              ///< Why it is not used (unreadable, empty, duplicate...).
    std::string summary_json;         ///< PreparedSummary as JSON (prepared and later).
    std::vector<std::uint64_t> keys;  ///< Global descriptor (described).
};

/// A candidate pair (source > target) and its result JSON (empty: not registered yet).
struct CampaignPairRow {
    std::int64_t source = 0, target = 0;
    double similarity = 0.0;
    std::string result_json;
};

/// A stone found by the match graph: its scans and the multi-view result (empty: not yet).
struct CampaignStoneRow {
    std::int64_t id = 0;
    std::vector<std::int64_t> scans;
    std::string result_json;
};

class CampaignStore {
public:
    /// Creates DIR (a new or empty folder) with `files` (absolute paths, no duplicates).
    static Expected<std::unique_ptr<CampaignStore>> create(const std::filesystem::path& dir,
                                                           const std::vector<std::string>& files);
    /// Opens an existing campaign; for writing it takes the folder's lock (fails kBusy when
    /// another job holds it).
    static Expected<std::unique_ptr<CampaignStore>> open(const std::filesystem::path& dir,
                                                         bool read_only);
    ~CampaignStore();
    CampaignStore(const CampaignStore&) = delete;
    CampaignStore& operator=(const CampaignStore&) = delete;

    const std::filesystem::path& dir() const;
    /// Where scan `id`'s prepared cloud is kept (PLY with normals).
    std::filesystem::path prepared_file(std::int64_t id) const;

    Expected<std::vector<CampaignScanRow>> scans() const;
    /// Records a scan's new state, problem, summary and keys.
    Expected<void> save_scan(const CampaignScanRow& row);
    /// Records several scans in one transaction.
    Expected<void> save_scans(const std::vector<CampaignScanRow>& rows);

    Expected<std::vector<CampaignPairRow>> pairs() const;
    /// Stores the candidate pairs (once: fails when some are stored already).
    Expected<void> set_candidates(const std::vector<CampaignPairRow>& pairs);
    Expected<void> save_pair_result(std::int64_t source, std::int64_t target,
                                    const std::string& result_json);

    Expected<std::vector<CampaignStoneRow>> stones() const;
    /// Stores the stones found (once) with the match graph's figures (`graph_json`).
    Expected<void> set_stones(const std::vector<CampaignStoneRow>& stones,
                              const std::string& graph_json);
    Expected<void> save_stone_result(std::int64_t id, const std::string& result_json);
    /// Forgets the stones and the match graph (repair of a damaged graph): the next job
    /// finds the stones again from the stored pair results.
    Expected<void> clear_stones();

    /// `PRAGMA integrity_check`'s answer ("ok" when intact).
    Expected<std::string> integrity_check() const;

    /// A named JSON value of the campaign (stage marks, figures); nullopt when not set.
    Expected<std::optional<std::string>> value(const std::string& key) const;
    Expected<void> set_value(const std::string& key, const std::string& json);

    struct Impl;

private:
    explicit CampaignStore(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace anascan::acquisition
