#include "anascan/processing/spatial/cloud_store.hpp"

#include <algorithm>
#include <string>
#include <system_error>
#include <utility>

#include "anascan/processing/io/ply.hpp"

namespace anascan {

CloudStore::CloudStore(CloudStoreConfig config) : config_(std::move(config)) {
    config_.max_loaded = std::max<std::size_t>(config_.max_loaded, 1);
}

CloudStore::~CloudStore() { remove_files(); }
CloudStore::CloudStore(CloudStore&&) noexcept = default;
CloudStore& CloudStore::operator=(CloudStore&& other) noexcept {
    if (this != &other) {
        remove_files();
        config_ = std::move(other.config_);
        loaded_ = std::move(other.loaded_);
        recency_ = std::move(other.recency_);
        position_ = std::move(other.position_);
        written_ = std::move(other.written_);
        stored_ = std::move(other.stored_);
        reloads_ = other.reloads_;
        other.written_.clear();
    }
    return *this;
}

std::filesystem::path CloudStore::file_of(std::size_t key) const {
    return config_.directory / ("cloud_" + std::to_string(key) + ".ply");
}

Expected<void> CloudStore::put(std::size_t key, PointCloud cloud) {
    auto shared = std::make_shared<const PointCloud>(std::move(cloud));
    if (spills()) {
        std::error_code ec;
        std::filesystem::create_directories(config_.directory, ec);
        if (ec) {
            return fail(ErrorCode::kIo, config_.directory.string() +
                                            ": cannot create the spill directory: " + ec.message());
        }
        const std::filesystem::path path = file_of(key);
        if (auto written = io::write_ply(path, *shared); !written) return written;
        if (!stored_.contains(key)) written_.push_back(path);
    }
    stored_.insert(key);
    loaded_[key] = std::move(shared);
    touch(key);
    evict();
    return {};
}

Expected<std::shared_ptr<const PointCloud>> CloudStore::get(std::size_t key) {
    if (const auto it = loaded_.find(key); it != loaded_.end()) {
        touch(key);
        return it->second;
    }
    if (!stored_.contains(key)) {
        return fail(ErrorCode::kInvalidArgument,
                    "cloud store: nothing stored under key " + std::to_string(key));
    }
    Expected<io::PlyData> read = io::read_ply(file_of(key));
    if (!read) return fail(read.error().code, "cloud store: " + read.error().message);
    ++reloads_;
    auto shared = std::make_shared<const PointCloud>(std::move(read->cloud));
    loaded_[key] = shared;
    touch(key);
    evict();
    return shared;
}

bool CloudStore::contains(std::size_t key) const { return stored_.contains(key); }

std::size_t CloudStore::loaded_count() const { return loaded_.size(); }

void CloudStore::touch(std::size_t key) {
    if (!spills()) return;
    if (const auto it = position_.find(key); it != position_.end()) recency_.erase(it->second);
    recency_.push_front(key);
    position_[key] = recency_.begin();
}

void CloudStore::evict() {
    while (spills() && recency_.size() > config_.max_loaded) {
        const std::size_t oldest = recency_.back();
        recency_.pop_back();
        position_.erase(oldest);
        loaded_.erase(oldest);
    }
}

void CloudStore::remove_files() {
    for (const std::filesystem::path& path : written_) {
        std::error_code ignored;
        std::filesystem::remove(path, ignored);
    }
    written_.clear();
}

}  // namespace anascan
