// RecordFile and the byte layout of spilled patches and matching results (raw, this
// process only: written and read by the same build).
#include "registration/batch/records.hpp"

#include <cstring>
#include <type_traits>
#include <utility>

namespace anascan::detail {
namespace {

template <typename T>
void put(Bytes& out, const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(out.data() + at, &value, sizeof(T));
}

void put_vector(Bytes& out, const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) put(out, v[k]);
}

// Reads in order; a short record reads as zeros (and `ok` turns false).
struct Reader {
    const Bytes& bytes;
    std::size_t at = 0;
    bool ok = true;

    template <typename T>
    T get() {
        T value{};
        if (at + sizeof(T) > bytes.size()) {
            ok = false;
            return value;
        }
        std::memcpy(&value, bytes.data() + at, sizeof(T));
        at += sizeof(T);
        return value;
    }
    Eigen::Vector3d get_vector() {
        Eigen::Vector3d v;
        for (int k = 0; k < 3; ++k) v[k] = get<double>();
        return v;
    }
};

}  // namespace

RecordFile::RecordFile(std::filesystem::path path) : path_(std::move(path)) {
    if (path_.empty()) return;
    std::error_code ignored;
    std::filesystem::create_directories(path_.parent_path(), ignored);
    file_.reset(std::fopen(path_.c_str(), "w+b"));
    if (!file_) error_ = path_.string() + ": cannot create the spill file";
}

RecordFile::~RecordFile() {
    if (path_.empty()) return;
    file_.reset();
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
}

std::size_t RecordFile::append(const Bytes& bytes) {
    const std::size_t number = size();
    offsets_.push_back(offsets_.back() + bytes.size());
    if (path_.empty()) {
        memory_.push_back(bytes);
    } else if (!file_ || std::fseek(file_.get(), 0, SEEK_END) != 0 ||
               std::fwrite(bytes.data(), 1, bytes.size(), file_.get()) != bytes.size()) {
        if (error_.empty()) error_ = path_.string() + ": cannot write the spill file";
    }
    return number;
}

Bytes RecordFile::read(std::size_t number) {
    if (number >= size()) return {};
    if (path_.empty()) return memory_[number];
    Bytes bytes(offsets_[number + 1] - offsets_[number]);
    if (!file_ || std::fseek(file_.get(), static_cast<long>(offsets_[number]), SEEK_SET) != 0 ||
        std::fread(bytes.data(), 1, bytes.size(), file_.get()) != bytes.size()) {
        if (error_.empty()) error_ = path_.string() + ": cannot read the spill file";
        return {};
    }
    return bytes;
}

Bytes to_bytes(const std::vector<FeaturePatch>& patches) {
    Bytes out;
    out.reserve(8 + patches.size() * sizeof(FeaturePatch));
    put(out, static_cast<std::uint64_t>(patches.size()));
    for (const FeaturePatch& p : patches) {
        put(out, static_cast<std::uint64_t>(p.radius_index));
        put(out, p.side);
        put(out, static_cast<std::uint64_t>(p.level));
        put(out, p.mean_volume);
        put_vector(out, p.barycentre_m);
        put_vector(out, p.normal);
        put_vector(out, p.extent_m);
        put(out, static_cast<std::uint64_t>(p.site_count));
    }
    return out;
}

std::vector<FeaturePatch> patches_from(const Bytes& bytes) {
    Reader in{bytes};
    const auto count = in.get<std::uint64_t>();
    std::vector<FeaturePatch> patches;
    for (std::uint64_t k = 0; k < count && in.ok; ++k) {
        FeaturePatch& p = patches.emplace_back();
        p.radius_index = in.get<std::uint64_t>();
        p.side = in.get<CurvatureSide>();
        p.level = in.get<std::uint64_t>();
        p.mean_volume = in.get<double>();
        p.barycentre_m = in.get_vector();
        p.normal = in.get_vector();
        p.extent_m = in.get_vector();
        p.site_count = in.get<std::uint64_t>();
    }
    if (!in.ok) patches.clear();
    return patches;
}

Bytes to_bytes(const FeatureMatchingResult& matching) {
    Bytes out;
    put(out, static_cast<std::uint64_t>(matching.candidate_count));
    put(out, static_cast<std::uint64_t>(matching.consistent_count));
    put(out, static_cast<std::uint64_t>(matching.hypotheses.size()));
    for (const PoseHypothesis& h : matching.hypotheses) {
        for (int k = 0; k < 16; ++k) put(out, h.T_target_source.matrix()(k / 4, k % 4));
        put(out, h.score);
        put(out, h.rms_m);
        put(out, static_cast<std::uint64_t>(h.inliers.size()));
        for (const FeatureCorrespondence& c : h.inliers) put(out, c);
    }
    return out;
}

FeatureMatchingResult matching_from(const Bytes& bytes) {
    Reader in{bytes};
    FeatureMatchingResult m;
    m.candidate_count = in.get<std::uint64_t>();
    m.consistent_count = in.get<std::uint64_t>();
    const auto count = in.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < count && in.ok; ++k) {
        PoseHypothesis& h = m.hypotheses.emplace_back();
        for (int e = 0; e < 16; ++e) h.T_target_source.matrix()(e / 4, e % 4) = in.get<double>();
        h.score = in.get<double>();
        h.rms_m = in.get<double>();
        const auto inliers = in.get<std::uint64_t>();
        for (std::uint64_t c = 0; c < inliers && in.ok; ++c) {
            h.inliers.push_back(in.get<FeatureCorrespondence>());
        }
    }
    if (!in.ok) m.hypotheses.clear();
    return m;
}

}  // namespace anascan::detail
