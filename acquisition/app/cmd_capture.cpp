// anascan capture --device DEV --session DIR: a scanning session. With a simulated scanner
// the simulated operator walks around the block (N views, turned over after K); with a
// real scanner each view waits for the operator (Enter; not when stdin is no terminal).
// Prints each acknowledged scan and its registration as they happen. The device is opened
// before the session folder is touched; Ctrl-C stops after the scan in flight.
#include <signal.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <thread>

#include "anascan/acquisition/assembly/group_pulls.hpp"
#include "anascan/acquisition/capture/capture_session.hpp"
#include "anascan/acquisition/capture/stone_check.hpp"
#include "anascan/acquisition/coverage/session_coverage.hpp"
#include "anascan/drivers/scanner.hpp"
#include "anascan/scanner_sources/scanner_source.hpp"
#include "capture_summary.hpp"
#include "commands.hpp"
#include "guided_tour.hpp"

namespace anascan::cli {
namespace {

using acquisition::CaptureSession;

struct CaptureOptions {
    std::string device;
    std::string session;
    std::string scene;
    int views = -1;       ///< -1: as the tour needs (resolve_tour).
    int flip_after = -1;  ///< -1: half the views.
    std::uint64_t tour_seed = 1;
    double distance_m = 1.1;
    bool no_register = false;
    bool lengths_from_device = false;  ///< LiveRegistrationConfig::lengths_from_device.
    bool no_coverage = false;
    bool mix_stones = false;  ///< Add to a session of another stone without asking.
    int sim_unplug_after = -1;
    scanner_sources::ScannerSettings settings;  ///< Only the fields given on the command line.
    double reconnect_timeout_s = 10.0;
    double operator_pause_s = 0.0;  ///< Simulated operator's walk between views.
    /// Simulated operator: "fixed" circle, "footprint" walk or "guided" by hints.
    std::string tour = "fixed";
    double target_coverage_percent = 99.0;  ///< A guided tour stops here.
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

/// Set by SIGINT (Ctrl-C): the capture loop stops after the scan in flight.
std::atomic<bool> g_interrupted{false};

void on_interrupt(int) {
    g_interrupted = true;
    struct sigaction again {};
    again.sa_handler = SIG_DFL;  // A second Ctrl-C ends the process at once.
    ::sigaction(SIGINT, &again, nullptr);
}

/// Catches Ctrl-C for the lifetime of the object (no SA_RESTART: a waiting prompt returns).
class InterruptGuard {
public:
    InterruptGuard() {
        g_interrupted = false;
        struct sigaction action {};
        action.sa_handler = on_interrupt;
        ::sigemptyset(&action.sa_mask);
        ::sigaction(SIGINT, &action, &previous_);
    }
    ~InterruptGuard() { ::sigaction(SIGINT, &previous_, nullptr); }
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

private:
    struct sigaction previous_ {};
};

/// Opens the scanner now, before any prompt or session folder, so that a missing device
/// or an unknown scene fails at once; the capture session then takes this opened scanner
/// (and reopens through `open` after an unplug).
acquisition::ScannerOpener open_now(const std::string& uri, acquisition::ScannerOpener open) {
    auto opened = open();
    if (!opened)
        throw CommandFailed(opened.error().message + " (see `anascan devices`; nothing was " +
                            "written)");
    auto first = std::make_shared<std::unique_ptr<drivers::Scanner>>(std::move(*opened));
    spdlog::debug("{}: opened", uri);
    return [first, open]() -> Expected<std::unique_ptr<drivers::Scanner>> {
        if (*first) return std::move(*first);
        return open();
    };
}

/// A real scanner: the operator places it and presses Enter (q or end of input stops).
/// Without a terminal on stdin nobody can press Enter: each view is captured at once.
bool operator_ready(int view, int views) {
    if (::isatty(STDIN_FILENO) == 0) return !g_interrupted;
    std::printf("place the scanner for view %d of %d and press Enter (q to stop) ", view + 1,
                views);
    std::fflush(stdout);
    std::string line;
    if (!std::getline(std::cin, line)) return false;
    return line != "q" && !g_interrupted;
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

/// At a terminal the operator answers; without one nobody can, and the answer is no.
bool operator_accepts_other_stone(const std::string& what) {
    if (::isatty(STDIN_FILENO) == 0) return false;
    std::printf("%s.\nadd the new scans to this session anyway? [y/N] ", what.c_str());
    std::fflush(stdout);
    std::string answer;
    return std::getline(std::cin, answer) && (answer == "y" || answer == "yes");
}

/// Another stone: the operator's answer (at a terminal), or --mix-stones. Refused, the
/// scans this capture added outside the model (`model_group`) are excluded (kept on disk)
/// and the capture ends.
void decide_on_other_stone(CaptureSession& session, const CaptureOptions& o,
                           const acquisition::StoneCheck& check, int already) {
    const std::string what = o.session + ": another stone? " + check.message;
    if (o.mix_stones || operator_accepts_other_stone(what)) {
        std::printf("%s; added anyway%s\n", what.c_str(), o.mix_stones ? " (--mix-stones)" : "");
        return;
    }
    const auto scans = session.store().scans();
    std::vector<std::int64_t> out =
        scans ? acquisition::scans_outside_model(*scans, already, check.model_group)
              : std::vector<std::int64_t>{};
    if (out.empty()) out.push_back(check.seq);
    for (const std::int64_t seq : out) (void)session.exclude(seq, true);
    session.wait_until_idle();
    const std::string kept = out.size() == 1
                                 ? "Scan " + std::to_string(check.seq) + " is"
                                 : std::to_string(out.size()) + " scans of this capture are";
    throw CommandFailed(what + ". " + kept +
                        " kept on disk but excluded, nothing was mixed into the model. "
                        "Use a new --session for a new stone, or --mix-stones to add these "
                        "scans anyway");
}

/// The first scan added to a session with a model, once registered: a scan that joined
/// no part of the stone and shows another object is asked about (refused without a
/// terminal, unless --mix-stones); a refused scan is excluded (kept on disk) and the
/// capture ends. Returns the line for the summary when the scan did not join; while the
/// stone is not confirmed, `model_seq` is a scan of the model (0 otherwise).
std::string confirm_same_stone(CaptureSession& session, const CaptureOptions& o,
                               const std::string& uri, int already, std::int64_t& model_seq) {
    model_seq = 0;
    auto scans = session.store().scans();
    if (!scans || scans->empty()) return {};
    const std::int64_t seq = scans->back().seq;
    auto check = acquisition::check_stone_of_scan(session.store(), seq);
    if (!check) {
        spdlog::warn("could not compare scan {} with the stone: {}", seq, check.error().message);
        return {};
    }
    using acquisition::StoneCheckOutcome;
    if (check->outcome == StoneCheckOutcome::kJoined ||
        check->outcome == StoneCheckOutcome::kNoModel)
        return {};
    (void)session.store().add_event("stone-check", uri,
                                    std::string(to_string(check->outcome)) + ": " + check->message);
    if (check->outcome != StoneCheckOutcome::kOtherStone) {
        std::printf("%s\n", check->message.c_str());
        model_seq = check->model_scan;
        return check->message;
    }
    decide_on_other_stone(session, o, *check, already);
    return o.session + ": another stone? " + check->message + "; added anyway";
}

/// A later scan of a capture whose first scan joined no part of the stone, once registered:
/// true when it joined the model (the stone is confirmed, nothing more to check). A scan the
/// registrar fitted onto the model and then took out as contradicting it is asked about as
/// the first scan is.
bool later_scan_joins_stone(CaptureSession& session, const CaptureOptions& o,
                            const std::string& uri, int already, std::int64_t model_seq) {
    auto scans = session.store().scans();
    if (!scans || scans->empty()) return false;
    auto check = acquisition::check_later_scan(session.store(), scans->back().seq, model_seq);
    if (!check) {
        spdlog::warn("could not compare scan {} with the stone: {}", scans->back().seq,
                     check.error().message);
        return false;
    }
    if (check->outcome == acquisition::StoneCheckOutcome::kJoined) return true;
    if (check->outcome != acquisition::StoneCheckOutcome::kOtherStone) return false;
    (void)session.store().add_event("stone-check", uri, "other-stone: " + check->message);
    decide_on_other_stone(session, o, *check, already);
    return true;
}

/// The simulated operator walks on for the pause, unless Ctrl-C comes first.
void operator_pause(double pause_s) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(pause_s);
    while (!g_interrupted && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

/// The command that goes on where an interrupted capture stopped.
std::string resume_command(const CaptureOptions& o) {
    std::string command = "anascan capture --device " + o.device + " --session " + o.session;
    if (!o.scene.empty()) command += " --scene " + o.scene;
    if (o.tour != "fixed") command += " --tour " + o.tour;
    return command + " --views " + std::to_string(o.views);
}

std::string scan_list(const std::vector<std::int64_t>& seqs) {
    std::string out;
    for (std::size_t k = 0; k < seqs.size(); ++k)
        out += (k == 0 ? "" : k + 1 == seqs.size() ? " and " : ", ") + std::to_string(seqs[k]);
    return out;
}

/// How much of the session the model (its largest group) holds: exit code 3 for no model
/// or an unconfirmed pair (seen on a 0.8 m block: scans 2 and 4 joined 103 mm apart at
/// 0.005°), a warning for a partial one.
/// Each scan of each group against the rest of its group at once: one that slid along a
/// face is flagged (out of the model) before the coverage and the summary.
void flag_pulled_scans(acquisition::SessionStore& store) {
    auto pulls = acquisition::group_pulls(store, {}, [](int group, std::size_t scans) {
        spdlog::info("checking each scan of group {} against its other {} scans", group, scans - 1);
    });
    if (!pulls) {
        spdlog::warn("the final check of the groups did not run: {}", pulls.error().message);
        return;
    }
    for (const acquisition::GroupPull& p : *pulls)
        if (p.pull.pulled) spdlog::error("{}", p.message());
    if (auto flagged = acquisition::flag_pulled(store, *pulls); !flagged)
        spdlog::warn("the flags of the final check were not saved: {}", flagged.error().message);
}

void check_model(const acquisition::SessionStore& store) {
    auto scans = store.scans();
    if (!scans || scans->size() < 2) return;
    const acquisition::ModelMembers m = acquisition::model_members(*scans);
    const std::string of = " of the " + std::to_string(m.active) + " scans";
    const std::string rest = " (" + std::to_string(m.flagged) + " flagged, " +
                             std::to_string(m.active - m.joined.size() - m.flagged) + " elsewhere)";
    switch (m.strength()) {
        case acquisition::ModelStrength::kNone:
            report_poor_result("no two" + of +
                               " were joined, so there is no model and no coverage: the views "
                               "need to overlap (or the device's scans are too sparse to match)");
            break;
        case acquisition::ModelStrength::kUnconfirmedPair:
            report_poor_result(
                "the model is only scans " + scan_list(m.joined) + of + rest +
                ", joined by one fit that no other scan confirms: two views of a flat face fit "
                "anywhere along it, so their placement is unverified; take views that overlap "
                "both, or register again");
            break;
        case acquisition::ModelStrength::kPartial:
            spdlog::warn("the model holds only {}{}{}: the rest is not in it", m.joined.size(), of,
                         rest);
            break;
        case acquisition::ModelStrength::kWhole:
            break;
    }
}

scanner_sources::SimulatedTour simulated_tour(const CaptureOptions& o) {
    return {.views = o.views,
            .flip_after = o.flip_after < 0 ? o.views / 2 : o.flip_after,
            .distance_m = o.distance_m,
            .seed = o.tour_seed,
            .follow_footprint = o.tour == "footprint"};
}

/// The number of views when the command line leaves it open: the footprint walk of a
/// simulated device takes as many as the block's outline needs (both sides, or one with
/// --flip-after 0); the other tours and a real scanner's operator take 24.
CaptureOptions resolve_tour(CaptureOptions o, const std::string& uri) {
    if (o.views > 0) return o;
    o.views = 24;
    if (o.tour != "footprint" || !scanner_sources::is_simulated(uri)) return o;
    auto per_side = scanner_sources::footprint_views_per_side(uri, simulated_tour(o));
    if (!per_side) fail_command(per_side.error());
    const bool turned_over = o.flip_after != 0;
    if (o.flip_after < 0) o.flip_after = *per_side;
    o.views = turned_over ? o.flip_after + *per_side : *per_side;
    std::printf("the simulated operator walks the block's footprint: %d views%s\n", o.views,
                turned_over
                    ? (", the stone turned over after " + std::to_string(o.flip_after)).c_str()
                    : "");
    return o;
}

[[noreturn]] void throw_interrupted(const acquisition::SessionStore& store,
                                    const CaptureOptions& o) {
    auto scans = store.scans();
    const std::size_t saved = scans ? scans->size() : 0;
    throw CommandInterrupted("stopped (Ctrl-C) after scan " + std::to_string(saved) +
                             "; the session is saved; resume with: " + resume_command(o));
}

void print_plan_times(const std::vector<double>& times_s) {
    if (times_s.empty()) return;
    const double worst = *std::max_element(times_s.begin(), times_s.end());
    std::printf("guided tour: %zu hints, each planned in at most %.2f s\n", times_s.size(), worst);
}

/// Views `from` to `to` (exclusive) of the session, as the fixed tour, the guided operator or
/// a real scanner's operator takes them; the error that stopped them, if any.
std::optional<Error> capture_views(CaptureSession& session, const CaptureOptions& o,
                                   const std::string& uri, GuidedOperator& guide, int from,
                                   int to) {
    const scanner_sources::SimulatedTour tour = simulated_tour(o);
    const bool simulated = scanner_sources::is_simulated(uri);
    const bool guided = simulated && o.tour == "guided";
    std::optional<Error> stopped;
    for (int i = from; i < to && !stopped && !g_interrupted; ++i) {
        if (!simulated && !operator_ready(i, o.views)) break;
        std::optional<acquisition::CaptureRequest> request;
        if (guided) {
            request = guide.next(session, i);
            if (!request) break;
        } else {
            if (scanner_sources::tour_turns_over_before(tour, i))
                std::printf("the stone is turned over before view %d\n", i + 1);
            request = scanner_sources::tour_request(tour, i);
        }
        stopped = capture_view(session, *request, o.reconnect_timeout_s);
        if (simulated && !stopped && i + 1 < o.views && o.operator_pause_s > 0.0)
            operator_pause(o.operator_pause_s);
    }
    return stopped;
}

std::size_t scan_count(CaptureSession& session) {
    auto scans = session.store().scans();
    return scans ? scans->size() : 0;
}

/// All views from `already` on; the first one added to a session that has scans is
/// registered and checked against the stone before the others (see confirm_same_stone),
/// unless --mix-stones says the answer beforehand (then nothing waits for the check). When
/// it joined no part of the stone, each later view is registered before the next is taken,
/// until one joins the model (later_scan_joins_stone).
std::optional<Error> capture_all_views(CaptureSession& session, const CaptureOptions& o,
                                       const std::string& uri, int already,
                                       std::string& stone_note) {
    GuidedOperator guide(simulated_tour(o), o.target_coverage_percent / 100.0);
    int from = already;
    if (already > 0 && !o.no_register && !o.mix_stones && already < o.views) {
        const auto stopped = capture_views(session, o, uri, guide, already, already + 1);
        if (stopped || g_interrupted) return stopped;
        session.wait_until_idle();
        std::int64_t model_seq = 0;
        stone_note = confirm_same_stone(session, o, uri, already, model_seq);
        for (from = already + 1; model_seq > 0 && from < o.views; ++from) {
            const std::size_t saved = scan_count(session);
            const auto later = capture_views(session, o, uri, guide, from, from + 1);
            if (later || g_interrupted) return later;
            if (scan_count(session) == saved) {  // The operator stopped, or the guide did.
                from = o.views;
                break;
            }
            session.wait_until_idle();
            if (later_scan_joins_stone(session, o, uri, already, model_seq)) model_seq = 0;
        }
    }
    const auto stopped = capture_views(session, o, uri, guide, from, o.views);
    if (scanner_sources::is_simulated(uri) && o.tour == "guided")
        print_plan_times(guide.plan_times_s());
    return stopped;
}

void run_capture(const CaptureOptions& given) {
    const std::string uri = device_uri(given);
    const CaptureOptions o = resolve_tour(given, uri);
    const scanner_sources::ScannerSource source{
        .uri = uri, .settings = o.settings, .sim_unplug_after = o.sim_unplug_after};
    auto opener = open_now(uri, scanner_sources::make_scanner_opener(source));
    auto store =
        acquisition::SessionStore::open(o.session, acquisition::SessionOpenMode::kCreateOrOpen);
    if (!store) fail_command(store.error());
    auto existing = (*store)->scans();
    if (!existing) fail_command(existing.error());
    const int already = static_cast<int>(existing->size());

    acquisition::CaptureSessionConfig config{.register_live = !o.no_register,
                                             .coverage_live = !o.no_coverage};
    config.registration.lengths_from_device = o.lengths_from_device;
    auto session = CaptureSession::start(std::move(*store), config, printing_sink());
    if (!session) fail_command(session.error());
    if (auto ok = (*session)->attach_scanner(uri, std::move(opener)); !ok) fail_command(ok.error());
    if (already > 0)
        std::printf("session %s has %d scans: resuming at view %d of %d\n", o.session.c_str(),
                    already, std::min(already, o.views) + 1, o.views);
    const InterruptGuard interrupt_guard;  // Ctrl-C stops after the scan in flight, until the end.
    std::string stone_note;
    const std::optional<Error> stopped = capture_all_views(**session, o, uri, already, stone_note);
    spdlog::info("capture done; waiting for registration to catch up");
    (*session)->wait_until_idle();
    if (!o.no_register) flag_pulled_scans((*session)->store());
    if (!o.no_register && !o.no_coverage) store_final_coverage((*session)->store());
    print_capture_summary((*session)->store());
    if (!stone_note.empty()) std::printf("stone check: %s\n", stone_note.c_str());
    if (stopped) throw CommandFailed("capture stopped: " + stopped->message);
    if (g_interrupted) throw_interrupted((*session)->store(), o);
    if (!o.no_register) check_model((*session)->store());
}

/// How the simulated operator walks (simulated devices only; a real scanner's operator
/// places it by hand).
void add_simulated_operator_options(CLI::App& cmd, CaptureOptions& opts) {
    cmd.add_option("--flip-after", opts.flip_after,
                   "Simulated operator turns the stone over after this many views "
                   "(default: half; 0: never)")
        ->check(CLI::Range(0, 10000));
    cmd.add_option("--distance-m", opts.distance_m,
                   "Simulated structured-light head to the block, m (default 1.1)")
        ->check(CLI::Range(0.5, 3.0));
    cmd.add_option("--tour-seed", opts.tour_seed, "Seed of the simulated operator's jitter");
    cmd.add_option("--tour", opts.tour,
                   "Simulated operator: 'fixed' (the default) circles the block's centre "
                   "(--views, --flip-after); 'footprint' walks along the block's outline at "
                   "--distance-m from the stone, with as many views as the outline needs "
                   "unless --views is given; 'guided' follows the next-best-view hints after "
                   "each scan, turns the stone over when they say so, and stops at "
                   "--target-coverage or after --views")
        ->check(CLI::IsMember({"footprint", "fixed", "guided"}));
    cmd.add_option("--target-coverage", opts.target_coverage_percent,
                   "Guided tour: stop once the coverage reaches this, percent (default 99)")
        ->check(CLI::Range(1.0, 100.0));
    cmd.add_option("--operator-pause-s", opts.operator_pause_s,
                   "Simulated operator: seconds spent walking to the next view after each "
                   "scan (default 0: back to back, the registration queue's worst case)")
        ->check(CLI::Range(0.0, 600.0));
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
    cmd->add_option("--views", opts->views,
                    "Views in the whole session (default 24; the footprint walk: as many "
                    "as the block's outline needs)")
        ->check(CLI::Range(1, 10000));
    add_simulated_operator_options(*cmd, *opts);
    cmd->add_option("--exposure-us", opts->settings.exposure_us, "Device exposure, microseconds");
    cmd->add_option("--angular-step-deg", opts->settings.angular_step_deg,
                    "Terrestrial scanner angular step, degrees");
    cmd->add_option("--max-range-m", opts->settings.max_range_m, "Farthest depth kept, m");
    cmd->add_flag("--no-register", opts->no_register, "Only capture and save (register later)");
    cmd->add_flag("--lengths-from-device", opts->lengths_from_device,
                  "Experimental: raise the live registration's lengths (voxel, gates, overlap "
                  "distances) to the noise measured on the first scan (docs/live-registration.md)");
    cmd->add_flag("--no-coverage", opts->no_coverage, "No live coverage");
    cmd->add_flag("--mix-stones", opts->mix_stones,
                  "Add to an existing session without checking that its new scans show "
                  "the same stone (default: register the first one before the next view and, "
                  "when it joins no part of the stone and its size or surface shows another "
                  "object, or the stone's model contradicts it, ask, or refuse without a "
                  "terminal; until a new scan joins the model, each is checked so)");
    cmd->add_option("--reconnect-timeout-s", opts->reconnect_timeout_s,
                    "How long to wait for a device that went away, s (default 10)")
        ->check(CLI::Range(0.0, 3600.0));
    cmd->add_option("--sim-unplug-after", opts->sim_unplug_after,
                    "Fault injection: the simulated device is unplugged during the capture "
                    "after this many")
        ->check(CLI::Range(0, 10000));
    cmd->callback([opts] { run_capture(*opts); });
}

}  // namespace anascan::cli
