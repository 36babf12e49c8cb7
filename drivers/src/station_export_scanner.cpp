#include "station_export_scanner.hpp"

#include <algorithm>
#include <deque>

namespace anascan::drivers {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

/// Not thread-safe (see Scanner).
class StationExportScanner final : public Scanner {
public:
    StationExportScanner(const std::filesystem::path& folder, StationFormat format,
                         std::vector<std::filesystem::path> files)
        : format_(std::move(format)), files_(files.begin(), files.end()) {
        info_ = DeviceInfo{.uri = format_.scheme + ":" + folder.string(),
                           .model = format_.model,
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
    Expected<void> read_next_file(const CaptureControl& control);

    StationFormat format_;
    DeviceInfo info_;
    Capabilities caps_;
    std::deque<std::filesystem::path> files_;
    std::deque<Scan> stations_;
    std::int64_t sequence_ = 0;
    bool closed_ = false;
};

Expected<void> StationExportScanner::read_next_file(const CaptureControl& control) {
    const std::filesystem::path file = files_.front();
    files_.pop_front();  // a bad file is reported once; the next capture reads the next file
    if (control.on_progress) control.on_progress({0.0, "reading " + file.filename().string()});
    auto stations = format_.read(file);
    if (!stations) return fail(stations.error());
    for (Scan& s : *stations) stations_.push_back(std::move(s));
    if (stations_.empty()) return fail(ErrorCode::kFormat, file.string() + ": no station");
    return {};
}

Expected<Scan> StationExportScanner::capture_scan(const CaptureControl& control) {
    if (closed_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
    if (control.stop.stop_requested())
        return fail(ErrorCode::kCancelled, info_.uri + ": cancelled");
    if (stations_.empty()) {
        if (files_.empty()) return fail(ErrorCode::kEmpty, info_.uri + ": no more stations");
        if (auto ok = read_next_file(control); !ok) return fail(ok.error());
    }
    Scan scan = std::move(stations_.front());
    stations_.pop_front();
    scan.meta.sequence = sequence_++;
    scan.meta.device_id = info_.uri;
    scan.meta.device_kind = DeviceKind::kTimeOfFlight;
    scan.meta.settings_json = settings_to_json({});
    if (!scan.meta.sensor_origin_scan_m) scan.meta.sensor_origin_scan_m = Eigen::Vector3d::Zero();
    if (control.on_progress) {
        const bool posed = scan.meta.T_world_scan.has_value();
        control.on_progress({1.0, "station " + scan.meta.id +
                                      (posed ? ""
                                             : " (no pose in the export: registered from "
                                               "its geometry)")});
    }
    return scan;
}

}  // namespace

Expected<std::unique_ptr<Scanner>> open_station_export_scanner(const std::filesystem::path& folder,
                                                               StationFormat format) {
    std::error_code ec;
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(folder, ec))
        if (e.is_regular_file() && lower(e.path().extension().string()) == format.extension)
            files.push_back(e.path());
    if (ec) return fail(ErrorCode::kIo, folder.string() + ": cannot list: " + ec.message());
    if (files.empty()) {
        return fail(ErrorCode::kEmpty,
                    folder.string() + ": no " + format.extension + " station export");
    }
    std::sort(files.begin(), files.end());
    return std::unique_ptr<Scanner>(
        new StationExportScanner(folder, std::move(format), std::move(files)));
}

Backend make_station_export_backend(StationFormat format, std::string description) {
    const std::string scheme = format.scheme;
    return Backend{.scheme = scheme,
                   .description = std::move(description),
                   .enumerate = [] { return std::vector<DeviceInfo>{}; },
                   .open = [format](const DeviceUri& uri) -> Expected<std::unique_ptr<Device>> {
                       auto scanner = open_station_export_scanner(uri.target, format);
                       if (!scanner) return fail(scanner.error());
                       return std::unique_ptr<Device>(std::move(*scanner));
                   }};
}

}  // namespace anascan::drivers
