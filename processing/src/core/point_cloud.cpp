#include "anascan/processing/core/point_cloud.hpp"

#include <cmath>

namespace anascan {
namespace {

template <class V>
bool empty_or_sized(const V& attribute, std::size_t n) {
    return attribute.empty() || attribute.size() == n;
}

template <class V>
void reserve_if_present(V& attribute, std::size_t n) {
    if (!attribute.empty()) attribute.reserve(n);
}

template <class V>
void select_into(const V& from, std::span<const std::size_t> indices, V& to) {
    if (from.empty()) return;
    to.reserve(indices.size());
    for (std::size_t i : indices) to.push_back(from[i]);
}

// Appends `from` to `to` when the attribute survives; otherwise clears `to`.
template <class V>
void append_attribute(V& to, const V& from, bool to_was_empty_cloud) {
    if (to_was_empty_cloud || (!to.empty() && !from.empty())) {
        to.insert(to.end(), from.begin(), from.end());
    } else {
        to.clear();
    }
}

bool is_finite(const Eigen::Vector3f& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

}  // namespace

bool PointCloud::attributes_consistent() const { return describe_inconsistency(*this).empty(); }

void PointCloud::reserve(std::size_t n) {
    positions.reserve(n);
    reserve_if_present(normals, n);
    reserve_if_present(colors, n);
    reserve_if_present(intensity, n);
    reserve_if_present(confidence, n);
}

std::string describe_inconsistency(const PointCloud& cloud) {
    const std::size_t n = cloud.positions.size();
    std::string problems;
    auto check = [&](const char* name, std::size_t size, bool ok) {
        if (ok) return;
        if (!problems.empty()) problems += "; ";
        problems += std::string(name) + " has " + std::to_string(size) + " entries for " +
                    std::to_string(n) + " points";
    };
    check("normals", cloud.normals.size(), empty_or_sized(cloud.normals, n));
    check("colors", cloud.colors.size(), empty_or_sized(cloud.colors, n));
    check("intensity", cloud.intensity.size(), empty_or_sized(cloud.intensity, n));
    check("confidence", cloud.confidence.size(), empty_or_sized(cloud.confidence, n));
    return problems;
}

PointCloud select(const PointCloud& cloud, std::span<const std::size_t> indices) {
    PointCloud out;
    out.origin_m = cloud.origin_m;
    select_into(cloud.positions, indices, out.positions);
    select_into(cloud.normals, indices, out.normals);
    select_into(cloud.colors, indices, out.colors);
    select_into(cloud.intensity, indices, out.intensity);
    select_into(cloud.confidence, indices, out.confidence);
    return out;
}

void append(PointCloud& cloud, const PointCloud& other) {
    const bool was_empty = cloud.empty();
    if (was_empty) cloud.origin_m = other.origin_m;
    const Eigen::Vector3f shift = (other.origin_m - cloud.origin_m).cast<float>();
    cloud.positions.reserve(cloud.size() + other.size());
    for (const Eigen::Vector3f& p : other.positions) cloud.positions.push_back(p + shift);
    append_attribute(cloud.normals, other.normals, was_empty);
    append_attribute(cloud.colors, other.colors, was_empty);
    append_attribute(cloud.intensity, other.intensity, was_empty);
    append_attribute(cloud.confidence, other.confidence, was_empty);
}

std::size_t remove_non_finite(PointCloud& cloud) {
    std::vector<std::size_t> keep;
    keep.reserve(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (is_finite(cloud.positions[i])) keep.push_back(i);
    }
    const std::size_t removed = cloud.size() - keep.size();
    if (removed > 0) cloud = select(cloud, keep);
    return removed;
}

Bounds local_bounds(const PointCloud& cloud) {
    Bounds b;
    if (cloud.empty()) return b;
    b.min = b.max = cloud.positions.front();
    for (const Eigen::Vector3f& p : cloud.positions) {
        b.min = b.min.cwiseMin(p);
        b.max = b.max.cwiseMax(p);
    }
    return b;
}

}  // namespace anascan
