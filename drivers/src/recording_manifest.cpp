#include "recording_manifest.hpp"

#include <nlohmann/json.hpp>

#include "anascan/processing/io/file_bytes.hpp"
#include "json_integer.hpp"

namespace anascan::drivers {
namespace {

using nlohmann::json;

json profile_json(const StreamProfile& p) {
    return {{"width", p.width},
            {"height", p.height},
            {"format", std::string(to_string(p.format))},
            {"frame_rate_hz", p.frame_rate_hz}};
}

void put_range(json& j, const char* key, const std::optional<NumericRange>& r) {
    if (r) j[key] = {r->min, r->max};
}

void get_range(const json& j, const char* key, std::optional<NumericRange>& r) {
    if (j.contains(key))
        r = NumericRange{j.at(key).at(0).get<double>(), j.at(key).at(1).get<double>()};
}

}  // namespace

std::string manifest_to_json(const RecordingManifest& m) {
    json caps = {{"can_stream", m.capabilities.can_stream},
                 {"can_capture_scan", m.capabilities.can_capture_scan},
                 {"profiles", json::array()}};
    for (const StreamProfile& p : m.capabilities.profiles)
        caps["profiles"].push_back(profile_json(p));
    put_range(caps, "exposure_us", m.capabilities.exposure_us);
    put_range(caps, "gain", m.capabilities.gain);
    put_range(caps, "angular_step_deg", m.capabilities.angular_step_deg);
    put_range(caps, "range_m", m.capabilities.range_m);
    const json j = {{"format", "anascan-recording"},
                    {"version", 1},
                    {"device",
                     {{"uri", m.device.uri},
                      {"model", m.device.model},
                      {"serial", m.device.serial},
                      {"kind", to_string(m.device.kind)},
                      {"is_camera", m.device.is_camera},
                      {"is_scanner", m.device.is_scanner}}},
                    {"capabilities", caps},
                    {"settings", json::parse(settings_to_json(m.settings))},
                    {"calibration", json::parse(m.calibration_json, nullptr, false).is_discarded()
                                        ? json::object()
                                        : json::parse(m.calibration_json)}};
    return j.dump(2) + "\n";
}

namespace {

// Typed look-ups: json::value() throws when a key holds another type ("version": {}).
bool is_recording_header(const json& j) {
    if (j.is_discarded() || !j.is_object()) return false;
    const auto format = j.find("format");
    const auto version = j.find("version");
    return format != j.end() && format->is_string() && *format == "anascan-recording" &&
           version != j.end() && version->is_number_integer() && *version == 1;
}

DeviceKind kind_from_string(const std::string& s) {
    for (DeviceKind k :
         {DeviceKind::kStructuredLight, DeviceKind::kTimeOfFlight, DeviceKind::kImported})
        if (s == to_string(k)) return k;
    return DeviceKind::kUnknown;
}

}  // namespace

Expected<RecordingManifest> manifest_from_json(const std::string& text,
                                               const std::filesystem::path& path) {
    const json j = json::parse(text, nullptr, false);
    if (!is_recording_header(j)) {
        return fail(ErrorCode::kFormat, path.string() + ": not an anascan recording (version 1)");
    }
    RecordingManifest m;
    std::string settings_text;
    try {
        const json& d = j.at("device");
        m.device = DeviceInfo{
            d.at("uri").get<std::string>(),    d.at("model").get<std::string>(),
            d.at("serial").get<std::string>(), kind_from_string(d.at("kind").get<std::string>()),
            d.at("is_camera").get<bool>(),     d.at("is_scanner").get<bool>()};
        const json& c = j.at("capabilities");
        m.capabilities.can_stream = c.at("can_stream").get<bool>();
        m.capabilities.can_capture_scan = c.at("can_capture_scan").get<bool>();
        for (const json& p : c.at("profiles")) {
            auto format = parse_pixel_format(p.at("format").get<std::string>());
            if (!format)
                return fail(ErrorCode::kFormat, path.string() + ": " + format.error().message);
            m.capabilities.profiles.push_back({json_integer<int>(p.at("width")),
                                               json_integer<int>(p.at("height")), *format,
                                               p.at("frame_rate_hz").get<double>()});
        }
        get_range(c, "exposure_us", m.capabilities.exposure_us);
        get_range(c, "gain", m.capabilities.gain);
        get_range(c, "angular_step_deg", m.capabilities.angular_step_deg);
        get_range(c, "range_m", m.capabilities.range_m);
        m.calibration_json = j.at("calibration").dump();
        settings_text = j.at("settings").dump();
    } catch (const json::exception& e) {
        return fail(ErrorCode::kFormat, path.string() + ": " + e.what());
    }
    auto settings = settings_from_json(settings_text, path.string());
    if (!settings) return fail(settings.error());
    m.settings = *settings;
    return m;
}

Expected<void> write_manifest(const std::filesystem::path& folder, const RecordingManifest& m) {
    const std::string text = manifest_to_json(m);
    return io::write_file_atomically(folder / "device.json",
                                     std::span<const char>(text.data(), text.size()));
}

Expected<RecordingManifest> read_manifest(const std::filesystem::path& folder) {
    const std::filesystem::path path = folder / "device.json";
    auto bytes = io::read_file_bytes(path);
    if (!bytes) {
        return fail(ErrorCode::kIo,
                    path.string() +
                        ": cannot read (is this a recording folder?): " + bytes.error().message);
    }
    return manifest_from_json(std::string(bytes->begin(), bytes->end()), path);
}

Expected<void> prepare_recording_folder(const std::filesystem::path& folder) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) return fail(ErrorCode::kIo, folder.string() + ": cannot create: " + ec.message());
    if (std::filesystem::exists(folder / "device.json") ||
        std::filesystem::exists(folder / "frames.bin")) {
        return fail(ErrorCode::kInvalidArgument,
                    folder.string() + ": already holds a recording; choose a new folder");
    }
    return {};
}

RecordingManifest as_played_back(RecordingManifest m, const std::filesystem::path& folder) {
    m.device.model += " (playback)";
    m.device.uri = "playback:" + folder.string();
    return m;
}

Expected<void> configure_played_back(RecordingManifest& m, bool closed,
                                     const DeviceSettings& requested) {
    if (closed) return fail(ErrorCode::kDisconnected, m.device.uri + ": closed");
    if (auto ok = validate_settings(requested, m.capabilities, m.device.uri); !ok) return ok;
    m.settings = merge_settings(m.settings, requested);
    return {};
}

}  // namespace anascan::drivers
