// libFuzzer harness for the PTX reader: any input gives either scans whose grids and clouds
// agree or an error naming the source and a line; never a crash.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "anascan/processing/io/ptx.hpp"

namespace {

void check_scan(const anascan::io::PtxScan& scan) {
    const anascan::RangeGrid& grid = scan.grid;
    const anascan::PointCloud& cloud = scan.scan.cloud;
    if (grid.rows <= 0 || grid.cols <= 0) std::abort();
    if (grid.point_index.size() != std::size_t(grid.rows) * std::size_t(grid.cols)) std::abort();
    if (!cloud.attributes_consistent() || cloud.intensity.size() != cloud.size()) std::abort();
    std::vector<int> seen(cloud.size(), 0);
    for (const std::int32_t index : grid.point_index) {
        if (index == anascan::RangeGrid::kNoSample) continue;
        if (index < 0 || std::size_t(index) >= cloud.size() || seen[index]++ != 0) std::abort();
    }
    for (const int count : seen) {
        if (count != 1) std::abort();
    }
    const auto& T = scan.scan.meta.T_world_scan;
    if (!T || !T->matrix().allFinite() || !scan.scan.meta.sensor_origin_scan_m) std::abort();
    const Eigen::Matrix3d R = T->linear();
    if (!(R.transpose() * R).isIdentity(1e-9)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const char> bytes(reinterpret_cast<const char*>(data), size);
    const auto scans = anascan::io::parse_ptx(bytes, "fuzz.ptx");
    if (!scans) {
        if (scans.error().message.rfind("fuzz.ptx: line ", 0) != 0) std::abort();
        return 0;
    }
    if (scans->empty()) std::abort();
    for (const anascan::io::PtxScan& scan : *scans) check_scan(scan);
    return 0;
}
