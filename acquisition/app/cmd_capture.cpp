// anascan capture --device DEV --session DIR: a scanning session. With a simulated scanner
// the simulated operator walks around the block (N views, turned over after K); with a
// real scanner each view waits for the operator (Enter). Prints each acknowledged scan
// and its registration as they happen.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <thread>

#include "anascan/acquisition/capture/capture_session.hpp"
#include "anascan/acquisition/coverage/session_coverage.hpp"
#include "anascan/scanner_sources/scanner_source.hpp"
#include "capture_summary.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

using acquisition::CaptureSession;

struct CaptureOptions {
    std::string device;
    std::string session;
    std::string scene;
    int views = 24;
    int flip_after = -1;  ///< -1: half the views.
    std::uint64_t tour_seed = 1;
    double distance_m = 1.1;
    bool no_register = false;
    bool no_coverage = false;
    int sim_unplug_after = -1;
    scanner_sources::ScannerSettings settings;  ///< Only the fields given on the command line.
    double reconnect_timeout_s = 10.0;
    double operator_pause_s = 0.0;  ///< Simulated operator's walk between views.
};

/// `sim:structured-light` + `--scene small-block` → `sim:structured-light/small-block`.
std::string device_uri(const CaptureOptions& o) {
    if (o.scene.empty()) return o.device;
    if (o.device.rfind("sim:", 0) != 0)
        throw CommandFailed("--scene " + o.scene +
                            ": only simulated devices (sim:...) look at a scene");
    if (o.device.find('/') != std::string::npos)
        throw CommandFailed("--scene " + o.scene + ": the device " + o.device +
                            " already names a scene");
    return o.device + "/" + o.scene;
}

/// A real scanner: the operator places it and presses Enter (q or end of input stops).
bool operator_ready(int view, int views) {
    std::printf("place the scanner for view %d of %d and press Enter (q to stop) ", view + 1,
                views);
    std::fflush(stdout);
    std::string line;
    if (!std::getline(std::cin, line)) return false;
    return line != "q";
}

/// Captures one view, retrying while the device is away (unplugged, silent) for at most
/// the reconnect timeout. Returns the error that ends the session, if any.
std::optional<Error> capture_view(CaptureSession& session,
                                  const acquisition::CaptureRequest& request,
                                  double reconnect_timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(reconnect_timeout_s);
    for (;;) {
        auto acknowledged = session.capture(request).get();
        if (acknowledged) return std::nullopt;
        const ErrorCode code = acknowledged.error().code;
        const bool device_away = code == ErrorCode::kDisconnected || code == ErrorCode::kTimeout;
        if (!device_away || std::chrono::steady_clock::now() > deadline)
            return acknowledged.error();
        spdlog::warn("waiting for the device to come back (up to {:.0f} s)", reconnect_timeout_s);
        std::this_thread::sleep_for(std::chrono::seconds(1));
    }
}

void run_capture(const CaptureOptions& o) {
    const std::string uri = device_uri(o);
    auto store =
        acquisition::SessionStore::open(o.session, acquisition::SessionOpenMode::kCreateOrOpen);
    if (!store) fail_command(store.error());
    auto existing = (*store)->scans();
    if (!existing) fail_command(existing.error());
    const int already = static_cast<int>(existing->size());

    const scanner_sources::SimulatedTour tour{
        .views = o.views,
        .flip_after = o.flip_after < 0 ? o.views / 2 : o.flip_after,
        .distance_m = o.distance_m,
        .seed = o.tour_seed};
    acquisition::CaptureSessionConfig config{.register_live = !o.no_register,
                                             .coverage_live = !o.no_coverage};
    auto session = CaptureSession::start(std::move(*store), config, printing_sink());
    if (!session) fail_command(session.error());
    const scanner_sources::ScannerSource source{
        .uri = uri, .settings = o.settings, .sim_unplug_after = o.sim_unplug_after};
    if (auto ok = (*session)->attach_scanner(uri, scanner_sources::make_scanner_opener(source));
        !ok)
        fail_command(ok.error());
    if (already > 0)
        std::printf("session %s has %d scans: resuming at view %d of %d\n", o.session.c_str(),
                    already, std::min(already, o.views) + 1, o.views);
    std::optional<Error> stopped;
    const bool simulated = scanner_sources::is_simulated(uri);
    for (int i = already; i < o.views && !stopped; ++i) {
        if (!simulated && !operator_ready(i, o.views)) break;
        if (scanner_sources::tour_turns_over_before(tour, i))
            std::printf("the stone is turned over before view %d\n", i + 1);
        stopped =
            capture_view(**session, scanner_sources::tour_request(tour, i), o.reconnect_timeout_s);
        if (simulated && !stopped && i + 1 < o.views && o.operator_pause_s > 0.0)
            std::this_thread::sleep_for(std::chrono::duration<double>(o.operator_pause_s));
    }
    spdlog::info("capture done; waiting for registration to catch up");
    (*session)->wait_until_idle();
    if (!o.no_register && !o.no_coverage) store_final_coverage((*session)->store());
    print_capture_summary((*session)->store());
    if (stopped) throw CommandFailed("capture stopped: " + stopped->message);
}

}  // namespace

void add_capture_command(CLI::App& app) {
    auto opts = std::make_shared<CaptureOptions>();
    auto* cmd = app.add_subcommand(
        "capture", "Run a scanning session: capture, save, register live, track coverage");
    cmd->add_option("--device", opts->device,
                    "Scanner URI (sim:structured-light, sim:tof, ...; see anascan devices)")
        ->required();
    cmd->add_option("--session", opts->session, "Session folder (created, or resumed)")->required();
    cmd->add_option("--scene", opts->scene,
                    "Scene of a simulated device (anascan sim list-scenes)");
    cmd->add_option("--views", opts->views, "Views in the whole session (default 24)")
        ->check(CLI::Range(1, 10000));
    cmd->add_option("--flip-after", opts->flip_after,
                    "Simulated operator turns the stone over after this many views "
                    "(default: half; 0: never)")
        ->check(CLI::Range(0, 10000));
    cmd->add_option("--distance-m", opts->distance_m,
                    "Simulated structured-light head to the block, m (default 1.1)")
        ->check(CLI::Range(0.5, 3.0));
    cmd->add_option("--tour-seed", opts->tour_seed, "Seed of the simulated operator's jitter");
    cmd->add_option("--exposure-us", opts->settings.exposure_us, "Device exposure, microseconds");
    cmd->add_option("--angular-step-deg", opts->settings.angular_step_deg,
                    "Terrestrial scanner angular step, degrees");
    cmd->add_option("--max-range-m", opts->settings.max_range_m, "Farthest depth kept, m");
    cmd->add_flag("--no-register", opts->no_register, "Only capture and save (register later)");
    cmd->add_flag("--no-coverage", opts->no_coverage, "No live coverage");
    cmd->add_option("--reconnect-timeout-s", opts->reconnect_timeout_s,
                    "How long to wait for a device that went away, s (default 10)")
        ->check(CLI::Range(0.0, 3600.0));
    cmd->add_option("--operator-pause-s", opts->operator_pause_s,
                    "Simulated operator: seconds spent walking to the next view after each "
                    "scan (default 0: back to back, the registration queue's worst case)")
        ->check(CLI::Range(0.0, 600.0));
    cmd->add_option("--sim-unplug-after", opts->sim_unplug_after,
                    "Fault injection: the simulated device is unplugged during the capture "
                    "after this many")
        ->check(CLI::Range(0, 10000));
    cmd->callback([opts] { run_capture(*opts); });
}

}  // namespace anascan::cli
