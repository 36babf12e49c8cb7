// register_scans' prepared data: clouds and feature sites through the CloudStore, and the
// features stage (in memory, or in two passes with the descriptors on disk in between).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <system_error>
#include <utility>

#include "anascan/processing/features/feature_patches.hpp"
#include "registration/batch/steps.hpp"

namespace anascan::detail {
namespace {

void report(const RegistrationProgress& progress, const std::string& message) {
    if (progress) progress(message);
}

void note_failure(PreparedScans& scans, const std::string& message) {
    if (scans.spill_error.empty()) scans.spill_error = message;
}

// ---- Descriptors on disk between the two passes (raw arrays, this process only) --------

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

template <typename T>
bool write_array(std::FILE* f, const std::vector<T>& v) {
    const std::uint64_t n = v.size();
    return std::fwrite(&n, sizeof n, 1, f) == 1 &&
           (n == 0 || std::fwrite(v.data(), sizeof(T), n, f) == n);
}

template <typename T>
bool read_array(std::FILE* f, std::vector<T>& v) {
    std::uint64_t n = 0;
    if (std::fread(&n, sizeof n, 1, f) != 1 || n > (std::uint64_t(1) << 32)) return false;
    v.resize(n);
    return n == 0 || std::fread(v.data(), sizeof(T), n, f) == n;
}

std::filesystem::path invariants_file(const ScanRegistrationConfig& config, std::size_t i) {
    return config.spill_directory / ("invariants_" + std::to_string(i) + ".bin");
}

bool save_invariants(const std::filesystem::path& path, const IntegralInvariantResult& r) {
    const File f(std::fopen(path.c_str(), "wb"));
    return f && write_array(f.get(), r.site_positions) && write_array(f.get(), r.site_normals) &&
           write_array(f.get(), r.volume) && write_array(f.get(), r.valid_bits);
}

// Reads back the arrays into `r`, whose other fields were kept in memory.
bool load_invariants(const std::filesystem::path& path, IntegralInvariantResult& r) {
    const File f(std::fopen(path.c_str(), "rb"));
    return f && read_array(f.get(), r.site_positions) && read_array(f.get(), r.site_normals) &&
           read_array(f.get(), r.volume) && read_array(f.get(), r.valid_bits);
}

// Every m-th site (at most `max_sites`), for the pooled saliency quantiles.
IntegralInvariantResult thinned(const IntegralInvariantResult& r, std::size_t max_sites) {
    IntegralInvariantResult out;
    out.status = r.status;
    out.radii_m = r.radii_m;
    const std::size_t n = r.volume.size();
    const std::size_t step =
        std::max<std::size_t>(1, (n + max_sites - 1) / std::max<std::size_t>(max_sites, 1));
    out.volume.reserve((n + step - 1) / step);
    out.valid_bits.reserve((n + step - 1) / step);
    for (std::size_t s = 0; s < n; s += step) {
        out.volume.push_back(r.volume[s]);
        out.valid_bits.push_back(r.valid_bits[s]);
    }
    return out;  // Only what saliency_levels reads: volume and valid_bits.
}

// Frees a vector's storage (`v = {}` would keep its capacity: it assigns an empty list).
template <typename T>
void release(std::vector<T>& v) {
    std::vector<T>().swap(v);
}

void strip_arrays(IntegralInvariantResult& r) {
    release(r.site_positions);
    release(r.site_normals);
    release(r.volume);
    release(r.valid_bits);
}

InvariantRadii shared_radii(const PreparedScans& scans, const GlobalRegistrationConfig& config) {
    double diagonal_m = 0.0;
    for (const ScanSummary& s : scans.summary) diagonal_m = std::max(diagonal_m, s.diagonal_m);
    return registration_radii_m(diagonal_m, config);
}

void describe_in_memory(PreparedScans& scans, const ScanRegistrationConfig& config,
                        const RegistrationProgress& progress) {
    const InvariantRadii radii_m = shared_radii(scans, config.global);
    std::vector<IntegralInvariantResult> invariants(scans.size());
    for (std::size_t i = 0; i < scans.size(); ++i) {
        if (!scans.usable(i)) continue;
        report(progress, "features of scan " + std::to_string(i));
        invariants[i] = describe_scan(*scans.cloud(i), radii_m, config.global);
    }
    scans.features = scan_features(std::move(invariants), scans.spacing_m, config.global);
}

// Pass 2 of one scan: patches at the pooled levels, sites into the store, arrays dropped.
void finish_spilled(PreparedScans& scans, std::size_t i, const SaliencyLevels& levels,
                    const ScanRegistrationConfig& config) {
    ScanFeatures& f = scans.features[i];
    f.spacing_m = scans.spacing_m[i];
    if (f.invariants.status != IntegralInvariantStatus::kOk) return;
    const std::filesystem::path file = invariants_file(config, i);
    if (!load_invariants(file, f.invariants)) {
        note_failure(scans, file.string() + ": cannot read the spilled descriptors");
        f.invariants.status = IntegralInvariantStatus::kInvalidInput;
        return;
    }
    std::error_code ignored;
    std::filesystem::remove(file, ignored);
    f.patches = extract_feature_patches(f.invariants, levels, config.global.patches);
    scans.patch_record[i] = scans.patch_records.append(to_bytes(f.patches.patches));
    release(f.patches.patches);
    PointCloud sites;
    sites.positions = std::move(f.invariants.site_positions);
    sites.normals = std::move(f.invariants.site_normals);
    if (auto put = scans.store.put(2 * i + 1, std::move(sites)); !put) {
        note_failure(scans, put.error().message);
    }
    strip_arrays(f.invariants);
}

void describe_spilled(PreparedScans& scans, const ScanRegistrationConfig& config,
                      const RegistrationProgress& progress) {
    const InvariantRadii radii_m = shared_radii(scans, config.global);
    scans.features.assign(scans.size(), {});
    scans.patch_records = RecordFile(config.spill_directory / "patches.bin");
    scans.patch_record.assign(scans.size(), 0);
    std::vector<IntegralInvariantResult> pooled;
    pooled.reserve(scans.size());
    const std::size_t sites_per_scan = std::max<std::size_t>(
        1, std::min(config.max_level_sites_per_scan,
                    config.max_level_sites_total / std::max<std::size_t>(scans.size(), 1)));
    for (std::size_t i = 0; i < scans.size(); ++i) {
        if (!scans.usable(i)) continue;
        report(progress, "features of scan " + std::to_string(i));
        IntegralInvariantResult r = describe_scan(*scans.cloud(i), radii_m, config.global);
        if (r.status == IntegralInvariantStatus::kOk) {
            pooled.push_back(thinned(r, sites_per_scan));
            if (!save_invariants(invariants_file(config, i), r)) {
                note_failure(scans, invariants_file(config, i).string() +
                                        ": cannot write the spilled descriptors");
                r.status = IntegralInvariantStatus::kInvalidInput;
            }
        }
        strip_arrays(r);
        scans.features[i].invariants = std::move(r);
    }
    std::vector<const IntegralInvariantResult*> valid;
    for (const IntegralInvariantResult& r : pooled) valid.push_back(&r);
    const SaliencyLevels levels = saliency_levels(valid, config.global.patches);
    for (std::size_t i = 0; i < scans.size(); ++i) finish_spilled(scans, i, levels, config);
    if (!scans.patch_records.error().empty()) note_failure(scans, scans.patch_records.error());
}

}  // namespace

std::shared_ptr<const PointCloud> PreparedScans::cloud(std::size_t i) {
    if (!usable(i)) return std::make_shared<const PointCloud>();
    Expected<std::shared_ptr<const PointCloud>> got = store.get(2 * i);
    if (got) return *got;
    note_failure(*this, got.error().message);
    return std::make_shared<const PointCloud>();
}

FeaturePatchResult PreparedScans::patches(std::size_t i) {
    FeaturePatchResult p = features[i].patches;
    if (patch_record.empty() || p.status != FeaturePatchStatus::kOk) return p;
    const Bytes bytes = patch_records.read(patch_record[i]);
    if (bytes.empty()) {
        note_failure(*this, patch_records.error());
        p.status = FeaturePatchStatus::kInvalidInput;
        return p;
    }
    p.patches = patches_from(bytes);
    return p;
}

ScanFeatures PreparedScans::full_features(std::size_t i) {
    ScanFeatures f = features[i];
    f.patches = patches(i);
    if (!store.spills() || !store.contains(2 * i + 1)) return f;
    Expected<std::shared_ptr<const PointCloud>> sites = store.get(2 * i + 1);
    if (!sites) {
        note_failure(*this, sites.error().message);
        f.invariants.status = IntegralInvariantStatus::kInvalidInput;
        return f;
    }
    f.invariants.site_positions = (*sites)->positions;
    f.invariants.site_normals = (*sites)->normals;
    return f;
}

void describe_all(PreparedScans& scans, const ScanRegistrationConfig& config,
                  const RegistrationProgress& progress) {
    if (scans.store.spills()) {
        describe_spilled(scans, config, progress);
    } else {
        describe_in_memory(scans, config, progress);
    }
}

}  // namespace anascan::detail
