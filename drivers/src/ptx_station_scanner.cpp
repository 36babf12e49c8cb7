#include "anascan/drivers/ptx_station_scanner.hpp"

#include <algorithm>
#include <deque>

#include "anascan/processing/io/ptx.hpp"

namespace anascan::drivers {
namespace {

bool is_ptx(const std::filesystem::path& p) {
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext == ".ptx";
}

/// Not thread-safe (see Scanner).
class PtxStationScanner final : public Scanner {
public:
    PtxStationScanner(std::filesystem::path folder, std::vector<std::filesystem::path> files)
        : files_(files.begin(), files.end()) {
        info_ = DeviceInfo{.uri = "ptx:" + folder.string(),
                           .model = "PTX station exports",
                           .serial = folder.filename().string(),
                           .kind = DeviceKind::kTimeOfFlight,
                           .is_scanner = true};
        caps_.can_capture_scan = true;
    }
    const DeviceInfo& info() const override { return info_; }
    const Capabilities& capabilities() const override { return caps_; }
    DeviceSettings settings() const override { return {}; }
    Expected<void> configure(const DeviceSettings& requested) override {
        if (closed_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
        return validate_settings(requested, caps_, info_.uri);  // an import has no settings
    }
    void close() override {
        closed_ = true;
        files_.clear();
        stations_.clear();
    }
    Expected<Scan> capture_scan(const CaptureControl& control) override;

private:
    DeviceInfo info_;
    Capabilities caps_;
    std::deque<std::filesystem::path> files_;
    std::deque<io::PtxScan> stations_;
    std::int64_t sequence_ = 0;
    bool closed_ = false;
};

Expected<Scan> PtxStationScanner::capture_scan(const CaptureControl& control) {
    if (closed_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
    if (control.stop.stop_requested())
        return fail(ErrorCode::kCancelled, info_.uri + ": cancelled");
    if (stations_.empty()) {
        if (files_.empty()) return fail(ErrorCode::kEmpty, info_.uri + ": no more stations");
        const std::filesystem::path file = files_.front();
        files_.pop_front();
        if (control.on_progress) control.on_progress({0.0, "reading " + file.filename().string()});
        auto stations = io::read_ptx(file);
        if (!stations) return fail(stations.error());
        for (io::PtxScan& s : *stations) stations_.push_back(std::move(s));
        if (stations_.empty()) return fail(ErrorCode::kEmpty, file.string() + ": no station");
    }
    Scan scan = std::move(stations_.front().scan);
    stations_.pop_front();
    scan.meta.sequence = sequence_++;
    scan.meta.device_id = info_.uri;
    scan.meta.device_kind = DeviceKind::kTimeOfFlight;
    scan.meta.settings_json = settings_to_json({});
    if (!scan.meta.sensor_origin_scan_m) scan.meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
    if (control.on_progress) control.on_progress({1.0, "station " + scan.meta.id});
    return scan;
}

}  // namespace

Expected<std::unique_ptr<Scanner>> open_ptx_station_scanner(const std::filesystem::path& folder) {
    std::error_code ec;
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(folder, ec))
        if (e.is_regular_file() && is_ptx(e.path())) files.push_back(e.path());
    if (ec) return fail(ErrorCode::kIo, folder.string() + ": cannot list: " + ec.message());
    if (files.empty()) return fail(ErrorCode::kEmpty, folder.string() + ": no .ptx station export");
    std::sort(files.begin(), files.end());
    return std::unique_ptr<Scanner>(new PtxStationScanner(folder, std::move(files)));
}

Backend make_ptx_backend() {
    return Backend{.scheme = "ptx",
                   .description = "terrestrial-scanner station exports, e.g. ptx:/data/site-a",
                   .enumerate = [] { return std::vector<DeviceInfo>{}; },
                   .open = [](const DeviceUri& uri) -> Expected<std::unique_ptr<Device>> {
                       auto scanner = open_ptx_station_scanner(uri.target);
                       if (!scanner) return fail(scanner.error());
                       return std::unique_ptr<Device>(std::move(*scanner));
                   }};
}

}  // namespace anascan::drivers
