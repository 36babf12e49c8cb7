// anascan devices [URI...] [--json]: what is connected (and what the given URIs open),
// with kind, model and capabilities.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/device_watcher.hpp"
#include "commands.hpp"
#include "device_registry_setup.hpp"

namespace anascan::cli {
namespace {

using nlohmann::json;

struct DevicesOptions {
    std::vector<std::string> uris;
    bool json_output = false;
    bool no_open = false;
    double watch_s = 0.0;
};

/// One listed device: what enumeration says, and what opening it says.
struct Listing {
    drivers::DeviceInfo info;
    std::optional<drivers::Capabilities> caps;
    std::optional<Error> open_error;
};

json range_json(const std::optional<drivers::NumericRange>& r) {
    return r ? json{r->min, r->max} : json(nullptr);
}

json listing_json(const Listing& l) {
    json j = {{"uri", l.info.uri},          {"model", l.info.model},
              {"serial", l.info.serial},    {"kind", to_string(l.info.kind)},
              {"camera", l.info.is_camera}, {"scanner", l.info.is_scanner}};
    if (l.caps) {
        json streams = json::array();
        for (const drivers::StreamProfile& p : l.caps->profiles)
            streams.push_back({{"width", p.width},
                               {"height", p.height},
                               {"format", std::string(drivers::to_string(p.format))},
                               {"frame_rate_hz", p.frame_rate_hz}});
        j["capabilities"] = {{"streams", streams},
                             {"exposure_us", range_json(l.caps->exposure_us)},
                             {"gain", range_json(l.caps->gain)},
                             {"angular_step_deg", range_json(l.caps->angular_step_deg)},
                             {"range_m", range_json(l.caps->range_m)},
                             {"horizontal_field_deg", range_json(l.caps->horizontal_field_deg)},
                             {"vertical_field_deg", range_json(l.caps->vertical_field_deg)}};
    }
    if (l.open_error)
        j["error"] = {{"code", std::string(to_string(l.open_error->code))},
                      {"message", l.open_error->message}};
    return j;
}

void print_range(const char* name, const std::optional<drivers::NumericRange>& r,
                 const char* unit) {
    if (r) std::printf("    %s: %g to %g %s\n", name, r->min, r->max, unit);
}

std::string rate_text(double rate_hz) {
    if (rate_hz <= 0.0) return "";
    char text[32];
    std::snprintf(text, sizeof(text), " at %g Hz", rate_hz);
    return text;
}

void print_listing(const Listing& l) {
    const char* role = l.info.is_scanner ? "scanner" : (l.info.is_camera ? "camera" : "device");
    std::printf("%s\n  %s, %s, model \"%s\"%s%s\n", l.info.uri.c_str(), role,
                to_string(l.info.kind), l.info.model.c_str(), l.info.serial.empty() ? "" : ", ",
                l.info.serial.c_str());
    if (l.open_error) std::printf("  cannot open: %s\n", l.open_error->message.c_str());
    if (!l.caps) return;
    for (const drivers::StreamProfile& p : l.caps->profiles)
        std::printf("    stream: %d x %d px %s%s\n", p.width, p.height,
                    std::string(drivers::to_string(p.format)).c_str(),
                    rate_text(p.frame_rate_hz).c_str());
    print_range("exposure", l.caps->exposure_us, "us");
    print_range("gain", l.caps->gain, "(device units)");
    print_range("angular step", l.caps->angular_step_deg, "deg");
    print_range("range", l.caps->range_m, "m");
    print_range("horizontal field", l.caps->horizontal_field_deg, "deg");
    print_range("vertical field", l.caps->vertical_field_deg, "deg");
    if (l.caps->can_capture_scan) std::printf("    captures scans\n");
}

Listing describe(const drivers::DeviceRegistry& registry, drivers::DeviceInfo info, bool open) {
    Listing l{std::move(info), std::nullopt, std::nullopt};
    if (!open) return l;
    auto device = registry.open(l.info.uri);
    if (!device) {
        l.open_error = device.error();
        return l;
    }
    const drivers::DeviceInfo opened = (*device)->info();
    l.info = opened;  // opening knows more (model, kind) than enumeration
    l.caps = (*device)->capabilities();
    (*device)->close();
    return l;
}

/// Prints arrivals and removals for `seconds` (devices present at the start arrive first).
void watch_devices(const drivers::DeviceRegistry& registry, double seconds, bool json_lines) {
    drivers::DeviceWatcher watcher(
        registry,
        [json_lines](const drivers::DeviceEvent& e) {
            const bool arrived = e.type == drivers::DeviceEventType::kArrived;
            if (json_lines) {
                const json j = {{"event", arrived ? "arrived" : "removed"},
                                {"uri", e.device.uri},
                                {"model", e.device.model}};
                std::printf("%s\n", j.dump().c_str());
            } else {
                std::printf("%s %s \"%s\"\n", arrived ? "arrived" : "removed", e.device.uri.c_str(),
                            e.device.model.c_str());
            }
            std::fflush(stdout);
        },
        std::chrono::milliseconds(200));
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

void run_devices(const DevicesOptions& o) {
    const drivers::DeviceRegistry registry = make_cli_registry();
    if (o.watch_s > 0.0) {
        watch_devices(registry, o.watch_s, o.json_output);
        return;
    }
    std::vector<Listing> listings;
    for (drivers::DeviceInfo& info : registry.enumerate())
        listings.push_back(describe(registry, std::move(info), !o.no_open));
    for (const std::string& uri : o.uris) {
        auto parsed = drivers::parse_device_uri(uri);
        if (!parsed) fail_command(parsed.error());
        listings.push_back(describe(registry, drivers::DeviceInfo{.uri = uri}, true));
        if (listings.back().open_error && o.uris.size() == 1 && !o.json_output)
            fail_command(*listings.back().open_error);
    }
    if (o.json_output) {
        json all = json::array();
        for (const Listing& l : listings) all.push_back(listing_json(l));
        std::printf("%s\n", all.dump(2).c_str());
        return;
    }
    if (listings.empty()) std::printf("no devices found (backends:");
    for (const drivers::Backend& b : registry.backends())
        if (listings.empty()) std::printf(" %s:", b.scheme.c_str());
    if (listings.empty()) std::printf(")\n");
    for (const Listing& l : listings) print_listing(l);
}

}  // namespace

void add_devices_command(CLI::App& app) {
    auto opts = std::make_shared<DevicesOptions>();
    auto* cmd = app.add_subcommand(
        "devices",
        "List connected devices (V4L2 cameras, supported USB devices, simulated devices) with "
        "URI, kind, model and capabilities; URIs given (ptx:/folder, playback:/folder, ...) "
        "are opened and described too");
    cmd->add_option("uri", opts->uris, "Device URIs to describe as well");
    cmd->add_flag("--json", opts->json_output, "Print a JSON array instead of text");
    cmd->add_flag("--no-open", opts->no_open,
                  "Do not open enumerated devices (no capabilities, but no side effects)");
    cmd->add_option("--watch", opts->watch_s,
                    "Print arrivals and removals (polled every 0.2 s) for this many seconds")
        ->check(CLI::PositiveNumber);
    cmd->callback([opts] { run_devices(*opts); });
}

}  // namespace anascan::cli
