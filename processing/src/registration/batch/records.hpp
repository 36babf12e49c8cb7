#pragma once
// Records of register_scans kept out of memory when spilling: byte strings appended to one
// file of the spill directory and read back by number (in memory without a directory),
// and the (de)serialisation of what goes there (feature patches, matching results).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "anascan/processing/features/feature_patches.hpp"
#include "anascan/processing/registration/global/global_registration.hpp"

namespace anascan::detail {

using Bytes = std::vector<unsigned char>;

class RecordFile {
public:
    RecordFile() = default;  ///< In memory.
    /// Records go to `path` (created; removed by the destructor); empty path: in memory.
    explicit RecordFile(std::filesystem::path path);
    ~RecordFile();
    RecordFile(RecordFile&&) noexcept = default;
    RecordFile& operator=(RecordFile&&) noexcept = default;

    /// Appends a record; returns its number (records are numbered from 0).
    std::size_t append(const Bytes& bytes);
    /// Record `number` (empty when it cannot be read; the failure is in `error`).
    Bytes read(std::size_t number);
    std::size_t size() const { return offsets_.size() - 1; }
    const std::string& error() const { return error_; }  ///< First failure, naming the file.

private:
    struct Closer {
        void operator()(std::FILE* f) const { std::fclose(f); }
    };
    std::filesystem::path path_;
    std::unique_ptr<std::FILE, Closer> file_;
    std::vector<std::uint64_t> offsets_{0};  // Record k: [offsets_[k], offsets_[k + 1]).
    std::vector<Bytes> memory_;
    std::string error_;
};

Bytes to_bytes(const std::vector<FeaturePatch>& patches);
std::vector<FeaturePatch> patches_from(const Bytes& bytes);
Bytes to_bytes(const FeatureMatchingResult& matching);
FeatureMatchingResult matching_from(const Bytes& bytes);

}  // namespace anascan::detail
