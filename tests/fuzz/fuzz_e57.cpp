// libFuzzer harness for the E57 reader: any input gives either scans whose clouds, grids
// and poses are consistent or an error naming the source and a byte offset; never a crash.
//
// The first input byte chooses the layer: odd, the rest is an E57 file as it is (so the
// page checks are fuzzed); even, the rest is the file's logical content, which the
// harness splits into pages with valid checksums (so the XML and the binary sections
// behind the checks are fuzzed too).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "anascan/processing/io/e57.hpp"
#include "io/e57/paged_file.hpp"

namespace {

void check_scan(const anascan::io::E57Scan& scan) {
    const anascan::RangeGrid& grid = scan.grid;
    const anascan::PointCloud& cloud = scan.scan.cloud;
    if (!cloud.attributes_consistent()) std::abort();
    if (cloud.size() + scan.invalid_count != scan.record_count) std::abort();
    if (grid.point_index.size() != std::size_t(grid.rows) * std::size_t(grid.cols)) std::abort();
    std::vector<int> seen(cloud.size(), 0);
    for (const std::int32_t index : grid.point_index) {
        if (index == anascan::RangeGrid::kNoSample) continue;
        if (index < 0 || std::size_t(index) >= cloud.size() || seen[std::size_t(index)]++ != 0)
            std::abort();
    }
    for (const auto& p : cloud.positions)
        if (!p.allFinite()) std::abort();
    const auto& T = scan.scan.meta.T_world_scan;
    if (T && !(T->linear().transpose() * T->linear()).isIdentity(1e-9)) std::abort();
}

std::vector<char> with_pages(std::span<const std::uint8_t> logical) {
    std::vector<std::uint8_t> copy(logical.begin(), logical.end());
    const std::uint64_t pages = std::max<std::uint64_t>(
        1, (copy.size() + anascan::io::e57::kPageDataBytes - 1) / anascan::io::e57::kPageDataBytes);
    if (copy.size() >= 24) {  // a physical length that matches, unless the fuzzer lies
        for (int i = 0; i < 8; ++i) copy[16 + i] = std::uint8_t((pages * 1024) >> (8 * i));
    }
    return anascan::io::e57::paginate(copy);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::span<const std::uint8_t> rest(data + 1, size - 1);
    std::vector<char> bytes;
    if (data[0] & 1u) {
        bytes.assign(rest.begin(), rest.end());
    } else {
        bytes = with_pages(rest);
    }
    const auto file = anascan::io::parse_e57(bytes, "fuzz.e57");
    if (!file) {
        if (file.error().message.rfind("fuzz.e57: byte ", 0) != 0) std::abort();
        return 0;
    }
    if (file->scans.empty()) std::abort();
    for (const anascan::io::E57Scan& scan : file->scans) check_scan(scan);
    return 0;
}
