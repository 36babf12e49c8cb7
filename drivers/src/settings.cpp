#include "anascan/drivers/settings.hpp"

#include <nlohmann/json.hpp>
#include <sstream>

#include "json_integer.hpp"

namespace anascan::drivers {
namespace {

std::string range_text(const NumericRange& r) {
    std::ostringstream s;
    s << "[" << r.min << ", " << r.max << "]";
    return s.str();
}

Expected<void> check_numeric(const std::optional<double>& value,
                             const std::optional<NumericRange>& range, const char* name,
                             std::string_view device) {
    if (!value) return {};
    std::ostringstream s;
    s << device << ": " << name << " " << *value;
    if (!range) {
        return fail(ErrorCode::kInvalidArgument, s.str() + ": the device has no such setting");
    }
    if (!range->contains(*value)) {
        return fail(ErrorCode::kInvalidArgument, s.str() + " outside " + range_text(*range));
    }
    return {};
}

Expected<void> check_profile(const std::optional<StreamProfile>& profile, const Capabilities& caps,
                             std::string_view device) {
    if (!profile) return {};
    for (const StreamProfile& p : caps.profiles) {
        const bool rate_ok = profile->frame_rate_hz == 0.0 || p.frame_rate_hz == 0.0 ||
                             profile->frame_rate_hz == p.frame_rate_hz;
        if (p.width == profile->width && p.height == profile->height &&
            p.format == profile->format && rate_ok) {
            return {};
        }
    }
    std::ostringstream s;
    s << device << ": stream " << profile->width << " x " << profile->height << " "
      << to_string(profile->format) << " is not offered (offered:";
    for (const StreamProfile& p : caps.profiles)
        s << " " << p.width << "x" << p.height << " " << to_string(p.format);
    s << ")";
    return fail(ErrorCode::kInvalidArgument, s.str());
}

}  // namespace

Expected<void> validate_settings(const DeviceSettings& requested, const Capabilities& caps,
                                 std::string_view device_name) {
    if (auto ok = check_profile(requested.profile, caps, device_name); !ok) return ok;
    const std::pair<const std::optional<double>*, const std::optional<NumericRange>*> checks[] = {
        {&requested.exposure_us, &caps.exposure_us},
        {&requested.gain, &caps.gain},
        {&requested.angular_step_deg, &caps.angular_step_deg},
        {&requested.min_range_m, &caps.range_m},
        {&requested.max_range_m, &caps.range_m},
        {&requested.horizontal_field_deg, &caps.horizontal_field_deg},
        {&requested.vertical_field_deg, &caps.vertical_field_deg}};
    const char* names[] = {"exposure_us",       "gain",        "angular_step_deg",
                           "min_range_m",       "max_range_m", "horizontal_field_deg",
                           "vertical_field_deg"};
    for (std::size_t i = 0; i < std::size(checks); ++i) {
        if (auto ok = check_numeric(*checks[i].first, *checks[i].second, names[i], device_name);
            !ok) {
            return ok;
        }
    }
    if (requested.min_range_m && requested.max_range_m &&
        *requested.min_range_m >= *requested.max_range_m) {
        return fail(ErrorCode::kInvalidArgument,
                    std::string(device_name) + ": min_range_m must be below max_range_m");
    }
    return {};
}

DeviceSettings merge_settings(DeviceSettings current, const DeviceSettings& requested) {
    if (requested.profile) current.profile = requested.profile;
    if (requested.exposure_us) current.exposure_us = requested.exposure_us;
    if (requested.gain) current.gain = requested.gain;
    if (requested.angular_step_deg) current.angular_step_deg = requested.angular_step_deg;
    if (requested.min_range_m) current.min_range_m = requested.min_range_m;
    if (requested.max_range_m) current.max_range_m = requested.max_range_m;
    if (requested.horizontal_field_deg)
        current.horizontal_field_deg = requested.horizontal_field_deg;
    if (requested.vertical_field_deg) current.vertical_field_deg = requested.vertical_field_deg;
    return current;
}

std::string settings_to_json(const DeviceSettings& settings) {
    nlohmann::json j = nlohmann::json::object();
    if (settings.profile) {
        j["profile"] = {{"width", settings.profile->width},
                        {"height", settings.profile->height},
                        {"format", std::string(to_string(settings.profile->format))},
                        {"frame_rate_hz", settings.profile->frame_rate_hz}};
    }
    if (settings.exposure_us) j["exposure_us"] = *settings.exposure_us;
    if (settings.gain) j["gain"] = *settings.gain;
    if (settings.angular_step_deg) j["angular_step_deg"] = *settings.angular_step_deg;
    if (settings.min_range_m) j["min_range_m"] = *settings.min_range_m;
    if (settings.max_range_m) j["max_range_m"] = *settings.max_range_m;
    if (settings.horizontal_field_deg) j["horizontal_field_deg"] = *settings.horizontal_field_deg;
    if (settings.vertical_field_deg) j["vertical_field_deg"] = *settings.vertical_field_deg;
    return j.dump();
}

namespace {

void read_optional(const nlohmann::json& j, const char* key, std::optional<double>& out) {
    if (j.contains(key)) out = j.at(key).get<double>();
}

}  // namespace

Expected<DeviceSettings> settings_from_json(std::string_view json, std::string_view source) {
    const nlohmann::json j = nlohmann::json::parse(json, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
        return fail(ErrorCode::kFormat, std::string(source) + ": settings are not a JSON object");
    }
    DeviceSettings s;
    try {
        if (j.contains("profile")) {
            const auto& p = j.at("profile");
            auto format = parse_pixel_format(p.at("format").get<std::string>());
            if (!format)
                return fail(ErrorCode::kFormat,
                            std::string(source) + ": " + format.error().message);
            s.profile =
                StreamProfile{json_integer<int>(p.at("width")), json_integer<int>(p.at("height")),
                              *format, p.value("frame_rate_hz", 0.0)};
        }
        read_optional(j, "exposure_us", s.exposure_us);
        read_optional(j, "gain", s.gain);
        read_optional(j, "angular_step_deg", s.angular_step_deg);
        read_optional(j, "min_range_m", s.min_range_m);
        read_optional(j, "max_range_m", s.max_range_m);
        read_optional(j, "horizontal_field_deg", s.horizontal_field_deg);
        read_optional(j, "vertical_field_deg", s.vertical_field_deg);
    } catch (const nlohmann::json::exception& e) {
        return fail(ErrorCode::kFormat, std::string(source) + ": settings: " + e.what());
    }
    return s;
}

}  // namespace anascan::drivers
