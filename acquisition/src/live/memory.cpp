// LiveRegistrar::memory: what the registrar keeps, by part.
#include <vector>

#include "live/state.hpp"

namespace anascan::acquisition {
namespace {

template <typename T>
std::size_t bytes(const std::vector<T>& v) {
    return v.capacity() * sizeof(T);
}

std::size_t cloud_bytes(const PointCloud& c) {
    return bytes(c.positions) + bytes(c.normals) + bytes(c.colors) + bytes(c.intensity) +
           bytes(c.confidence);
}

std::size_t feature_bytes(const ScanFeatures& f) {
    const IntegralInvariantResult& i = f.invariants;
    return bytes(i.site_positions) + bytes(i.site_normals) + bytes(i.volume) + bytes(i.valid_bits) +
           bytes(f.patches.patches);
}

}  // namespace

LiveMemoryReport LiveRegistrar::memory() const {
    const State& s = *state_;
    LiveMemoryReport r{.scans = s.scans.size(), .links = s.links.size()};
    for (const live::ScanEntry& e : s.scans) {
        r.cloud_bytes += cloud_bytes(e.cloud);
        if (e.tree) r.tree_bytes += e.tree->memory_bytes();
        if (e.features) {
            r.feature_bytes += feature_bytes(*e.features);
            ++r.features_kept;
        }
    }
    for (const live::Link& l : s.links) r.link_bytes += bytes(l.correspondences);
    r.model_cache_bytes = cloud_bytes(s.model_cache.cloud);
    if (s.model_cache.tree) r.model_cache_bytes += s.model_cache.tree->memory_bytes();
    return r;
}

}  // namespace anascan::acquisition
