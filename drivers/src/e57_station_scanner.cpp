#include "anascan/drivers/e57_station_scanner.hpp"

#include "anascan/processing/io/e57.hpp"
#include "station_export_scanner.hpp"

namespace anascan::drivers {
namespace {

Expected<std::vector<Scan>> read_e57_stations(const std::filesystem::path& file) {
    auto e57 = io::read_e57(file);
    if (!e57) return fail(e57.error());
    std::vector<Scan> scans;
    for (io::E57Scan& s : e57->scans) {
        if (s.scan.cloud.empty()) {
            return fail(ErrorCode::kFormat,
                        file.string() + ": station '" + s.name + "' holds no points (" +
                            std::to_string(s.record_count) + " records, " +
                            std::to_string(s.invalid_count) +
                            " invalid); skipped, the next capture reads the next file");
        }
        scans.push_back(std::move(s.scan));
    }
    return scans;
}

StationFormat e57_format() {
    return {.scheme = "e57",
            .extension = ".e57",
            .model = "E57 station exports",
            .read = read_e57_stations};
}

}  // namespace

Expected<std::unique_ptr<Scanner>> open_e57_station_scanner(const std::filesystem::path& folder) {
    return open_station_export_scanner(folder, e57_format());
}

Backend make_e57_backend() {
    return make_station_export_backend(
        e57_format(), "terrestrial-scanner station exports, e.g. e57:/data/site-a");
}

}  // namespace anascan::drivers
