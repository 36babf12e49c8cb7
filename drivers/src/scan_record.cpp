#include "scan_record.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"
#include "json_integer.hpp"

namespace anascan::drivers {
namespace {

using nlohmann::json;

std::string stem(std::size_t index) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06zu", index);
    return name;
}

json meta_json(const ScanMetadata& m) {
    json j = {
        {"id", m.id},
        {"sequence", m.sequence},
        {"device_id", m.device_id},
        {"device_kind", to_string(m.device_kind)},
        {"time_ns",
         std::chrono::duration_cast<std::chrono::nanoseconds>(m.time.time_since_epoch()).count()},
        {"settings", m.settings_json},
        {"sensor_origin_scan_m", nullptr},
        {"T_world_scan", nullptr}};
    if (m.sensor_origin_scan_m) {
        const Eigen::Vector3d& o = *m.sensor_origin_scan_m;
        j["sensor_origin_scan_m"] = {o.x(), o.y(), o.z()};
    }
    if (m.T_world_scan) {
        json rows = json::array();
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) rows.push_back(m.T_world_scan->matrix()(r, c));
        j["T_world_scan"] = rows;  // row-major 4x4
    }
    return j;
}

DeviceKind kind_named(const std::string& s) {
    for (DeviceKind k :
         {DeviceKind::kStructuredLight, DeviceKind::kTimeOfFlight, DeviceKind::kImported})
        if (s == to_string(k)) return k;
    return DeviceKind::kUnknown;
}

ScanMetadata meta_from_json(const json& j) {
    ScanMetadata m;
    m.id = j.at("id").get<std::string>();
    m.sequence = json_integer<std::int64_t>(j.at("sequence"));
    m.device_id = j.at("device_id").get<std::string>();
    m.device_kind = kind_named(j.at("device_kind").get<std::string>());
    m.time = std::chrono::system_clock::time_point(
        std::chrono::duration_cast<std::chrono::system_clock::duration>(
            std::chrono::nanoseconds(json_integer<std::int64_t>(j.at("time_ns")))));
    m.settings_json = j.at("settings").get<std::string>();
    if (const json& o = j.at("sensor_origin_scan_m"); !o.is_null())
        m.sensor_origin_scan_m =
            Eigen::Vector3d(o.at(0).get<double>(), o.at(1).get<double>(), o.at(2).get<double>());
    if (const json& t = j.at("T_world_scan"); !t.is_null()) {
        Pose T = Pose::Identity();
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) T.matrix()(r, c) = t.at(4 * r + c).get<double>();
        m.T_world_scan = T;
    }
    return m;
}

}  // namespace

Expected<void> write_scan_record(const std::filesystem::path& folder, std::size_t index,
                                 const Scan& scan) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) return fail(ErrorCode::kIo, folder.string() + ": cannot create: " + ec.message());
    if (auto ok = io::write_ply(folder / (stem(index) + ".ply"), scan.cloud); !ok) return ok;
    const std::string text = meta_json(scan.meta).dump(2) + "\n";
    return io::write_file_atomically(folder / (stem(index) + ".json"),
                                     std::span<const char>(text.data(), text.size()));
}

std::vector<std::filesystem::path> list_scan_records(const std::filesystem::path& folder) {
    std::vector<std::filesystem::path> found;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(folder, ec))
        if (e.path().extension() == ".json") found.push_back(e.path());
    std::sort(found.begin(), found.end());
    return found;
}

Expected<Scan> read_scan_record(const std::filesystem::path& json_path) {
    auto bytes = io::read_file_bytes(json_path);
    if (!bytes) return fail(bytes.error());
    const json j = json::parse(bytes->begin(), bytes->end(), nullptr, false);
    if (j.is_discarded()) return fail(ErrorCode::kFormat, json_path.string() + ": not JSON");
    Scan scan;
    try {
        scan.meta = meta_from_json(j);
    } catch (const json::exception& e) {
        return fail(ErrorCode::kFormat, json_path.string() + ": scan metadata: " + e.what());
    }
    std::filesystem::path ply = json_path;
    ply.replace_extension(".ply");
    auto cloud = io::read_ply(ply);
    if (!cloud) return fail(cloud.error());
    scan.cloud = std::move(cloud->cloud);
    return scan;
}

}  // namespace anascan::drivers
