// libFuzzer harness for the PLY reader: parsing must never crash, leak or read outside the
// input; when it succeeds, writing the result and reading it back must give the same data
// (abort() otherwise, which libFuzzer reports as a crash).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <vector>

#include "anascan/processing/io/ply.hpp"

namespace {

using anascan::io::PlyData;

bool same_float(float a, float b) {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
    return std::memcmp(&a, &b, sizeof(float)) == 0;  // tells -0 from +0
}

bool same(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (!same_float(a[i], b[i])) return false;
    }
    return true;
}

bool same(const std::vector<Eigen::Vector3f>& a, const std::vector<Eigen::Vector3f>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            if (!same_float(a[i][k], b[i][k])) return false;
        }
    }
    return true;
}

bool same(const PlyData& a, const PlyData& b) {
    const anascan::PointCloud& x = a.cloud;
    const anascan::PointCloud& y = b.cloud;
    return x.origin_m == y.origin_m && same(x.positions, y.positions) &&
           same(x.normals, y.normals) && x.colors == y.colors && same(x.intensity, y.intensity) &&
           same(x.confidence, y.confidence) && a.triangles == b.triangles && a.format == b.format &&
           a.comments.size() == b.comments.size();
}

void check_round_trip(const PlyData& data) {
    if (!data.cloud.attributes_consistent()) std::abort();
    const std::vector<char> bytes = anascan::io::serialize_ply(
        data.cloud, data.triangles, {.format = data.format, .comments = data.comments});
    const anascan::Expected<PlyData> again = anascan::io::parse_ply(bytes, "round-trip.ply");
    if (!again || !same(data, *again)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const char> bytes(reinterpret_cast<const char*>(data), size);
    const anascan::Expected<PlyData> parsed = anascan::io::parse_ply(bytes, "fuzz.ply");
    if (parsed) check_round_trip(*parsed);
    return 0;
}
