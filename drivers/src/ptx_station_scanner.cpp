#include "anascan/drivers/ptx_station_scanner.hpp"

#include "anascan/processing/io/ptx.hpp"
#include "station_export_scanner.hpp"

namespace anascan::drivers {
namespace {

Expected<std::vector<Scan>> read_ptx_stations(const std::filesystem::path& file) {
    auto ptx = io::read_ptx(file);
    if (!ptx) return fail(ptx.error());
    std::vector<Scan> scans;
    for (io::PtxScan& s : *ptx) scans.push_back(std::move(s.scan));
    return scans;
}

StationFormat ptx_format() {
    return {.scheme = "ptx",
            .extension = ".ptx",
            .model = "PTX station exports",
            .read = read_ptx_stations};
}

}  // namespace

Expected<std::unique_ptr<Scanner>> open_ptx_station_scanner(const std::filesystem::path& folder) {
    return open_station_export_scanner(folder, ptx_format());
}

Backend make_ptx_backend() {
    return make_station_export_backend(
        ptx_format(), "terrestrial-scanner station exports, e.g. ptx:/data/site-a");
}

}  // namespace anascan::drivers
