#pragma once
/// \file
/// Point clouds by integer key, kept in memory or spilled to files and reloaded on demand.
///
/// Registering thousands of scans cannot keep every prepared cloud in memory (1000 scans of
/// 50k points with normals are 1.2 GB). With a directory, `put` writes the cloud there
/// (binary PLY, origin exact) and `get` reloads it when it is not among the
/// `max_loaded` most recently used clouds (LRU); without one, every cloud stays in memory
/// and nothing touches the disk. See docs/scan-registration.md ("Scale").
///
/// Not thread-safe: one caller at a time (register_scans calls it from its own thread).

#include <cstddef>
#include <filesystem>
#include <list>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan {

struct CloudStoreConfig {
    /// Where spilled clouds go (created when missing); empty: keep every cloud in memory.
    std::filesystem::path directory;
    std::size_t max_loaded = 8;  ///< Clouds held in memory at once when spilling (>= 1).
};

class CloudStore {
public:
    explicit CloudStore(CloudStoreConfig config = {});
    ~CloudStore();
    CloudStore(CloudStore&&) noexcept;
    CloudStore& operator=(CloudStore&&) noexcept;
    CloudStore(const CloudStore&) = delete;
    CloudStore& operator=(const CloudStore&) = delete;

    /// Stores `cloud` under `key` (replacing any earlier one). Fails (naming the file) when
    /// the spill file cannot be written.
    Expected<void> put(std::size_t key, PointCloud cloud);

    /// The cloud stored under `key`: from memory, or reloaded from its file (then the least
    /// recently used loaded cloud beyond `max_loaded` is dropped from memory; holders of
    /// its pointer keep it alive). Fails when nothing was stored under `key` or the file
    /// cannot be read (the message names it).
    Expected<std::shared_ptr<const PointCloud>> get(std::size_t key);

    bool contains(std::size_t key) const;
    bool spills() const { return !config_.directory.empty(); }
    std::size_t loaded_count() const;                      ///< Clouds currently held in memory.
    std::size_t reload_count() const { return reloads_; }  ///< Reads from files so far.
    /// Removes the spill files written by this store (also done by the destructor).
    void remove_files();

private:
    std::filesystem::path file_of(std::size_t key) const;
    void touch(std::size_t key);
    void evict();

    CloudStoreConfig config_;
    std::unordered_map<std::size_t, std::shared_ptr<const PointCloud>> loaded_;
    std::list<std::size_t> recency_;  // Most recent first (spill mode only).
    std::unordered_map<std::size_t, std::list<std::size_t>::iterator> position_;
    std::vector<std::filesystem::path> written_;
    std::unordered_set<std::size_t> stored_;
    std::size_t reloads_ = 0;
};

}  // namespace anascan
