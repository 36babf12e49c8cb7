// libFuzzer harness for the XYZ and PTS readers: any input gives either a consistent cloud
// or an error naming the source and a line; never a crash.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string_view>

#include "anascan/processing/io/text_points.hpp"

namespace {

void check(const anascan::Expected<anascan::PointCloud>& cloud, std::string_view source) {
    if (!cloud) {
        const std::string& message = cloud.error().message;
        if (message.rfind(std::string(source) + ": line ", 0) != 0) std::abort();
        return;
    }
    if (cloud->empty() || !cloud->attributes_consistent()) std::abort();
    for (const Eigen::Vector3f& p : cloud->positions) {
        if (!p.allFinite()) std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const char> bytes(reinterpret_cast<const char*>(data), size);
    check(anascan::io::parse_xyz(bytes, "fuzz.xyz"), "fuzz.xyz");
    check(anascan::io::parse_pts(bytes, "fuzz.pts"), "fuzz.pts");
    return 0;
}
