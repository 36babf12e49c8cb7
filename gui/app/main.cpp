// anascan-field: the operator's window in the scanning tent.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>

#include "field_app.hpp"

namespace {

/// The session: open or create, capture from the GUI (and headless, --capture-views).
void add_session_options(CLI::App& app, anascan::field::FieldAppConfig& config) {
    app.add_option("--session", config.session.dir,
                   "Session folder: shows its scans; the capture action records into it "
                   "(created at the first capture when absent)");
    app.add_option("--device", config.session.device,
                   "Device chosen at start (default: the device of the session's newest scan, "
                   "else sim:structured-light/small-block; anascan devices lists them)");
    app.add_option("--capture-views", config.headless.capture_views,
                   "Headless: this many captures through the capture action, rendering while "
                   "they run, then wait for registration (needs --session and --frames)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--tour-views", config.session.tour_views,
                   "Simulated operator: views of the walk around the block (default 24)")
        ->check(CLI::Range(1, 10000));
    app.add_option("--flip-after", config.session.flip_after,
                   "Simulated operator turns the stone over after this many views "
                   "(default: half the tour; 0: never)")
        ->check(CLI::Range(0, 10000));
    app.add_option("--angular-step-deg", config.session.angular_step_deg,
                   "Terrestrial scanner angular step, degrees")
        ->check(CLI::PositiveNumber);
    app.add_option("--session-timeout-s", config.headless.session_timeout_s,
                   "Headless: give up when the session has not settled after this long, s")
        ->check(CLI::PositiveNumber);
    app.add_option("--worker-nice", config.session.worker_nice,
                   "Capture, persistence and registration threads run this much nicer than the "
                   "drawing thread (0-19, default 10; 0: same priority)")
        ->check(CLI::Range(0, 19));
    app.add_option("--reregister-scan", config.headless.reregister_seq,
                   "Headless: once the session has settled, re-register this scan through the "
                   "scan list's action and wait for its result (needs --session and --frames)")
        ->check(CLI::PositiveNumber);
    app.add_flag("--connect", config.headless.connect_device,
                 "Headless: press the device panel's Connect at start (reads the device's "
                 "settings, starts the camera preview; needs --session)");
    app.add_option("--apply-setting", config.headless.apply_settings,
                   "Headless: once settled, type KEY=VALUE into the device panel's settings "
                   "(e.g. exposure_us=20000, max_range_m=2.5) and press Apply; repeatable");
    app.add_option("--upload-points-per-frame", config.session.upload_points_per_frame,
                   "A loaded scan goes to the GPU in steps of this many points a frame "
                   "(default 20000); 0: all in one frame, shuffled on the drawing thread")
        ->group("");  // hidden: for the before/after measurement
    // Fault injection for the tests: hidden (empty group).
    app.add_option("--sim-unplug-after", config.session.sim_unplug_after,
                   "Simulated device unplugged during the capture after this many")
        ->group("");
}

/// What the app reports besides the window: its state at the end, the session's events.
void add_report_options(CLI::App& app, anascan::field::FieldAppConfig& config) {
    app.add_option("--dump-state", config.dump_state_json,
                   "Write the view state (scan rows, coverage, status) as JSON at the end");
    app.add_flag("--log-events", config.session.log_events,
                 "Print the session's events on stdout as they come, one line each (saved, "
                 "registered, flagged, device errors): a terminal log beside the window");
}

/// The mesh view: its resolution, and the headless run's "Make the mesh".
void add_mesh_options(CLI::App& app, anascan::field::FieldAppConfig& config) {
    app.add_option("--mesh-resolution-mm", config.session.mesh_resolution_mm,
                   "Resolution of the mesh the operator asks for (M), millimetres (default 1)")
        ->check(CLI::Range(0.1, 100.0));
    app.add_flag("--make-mesh", config.headless.make_mesh,
                 "Headless: once settled, press \"Make the mesh\" and wait for it (needs "
                 "--session and --frames)");
}

/// The assembly view: a folder of block features, its proposals, the headless operator.
void add_assembly_options(CLI::App& app, anascan::field::AssemblyOptions& o) {
    app.add_option("--assembly", o.dir,
                   "Folder of anascan blocks features: the assembly view (blocks in 3D, "
                   "proposals, alignment) instead of the capture session")
        ->check(CLI::ExistingDirectory);
    app.add_option("--proposals", o.proposals,
                   "proposals.json of anascan blocks match (default: DIR/proposals.json)")
        ->check(CLI::ExistingFile);
    app.add_option("--assembly-out", o.out,
                   "Folder \"Accept and save\" writes (default: DIR/assembly)");
    app.add_option("--fixed", o.fixed, "Blocks that stay in place (default: the first)");
    app.add_option("--click-block", o.click_blocks,
                   "Headless: once loaded, click where this block's centre shows in the view "
                   "(the face in front is picked; a face of another block then pairs with it)");
    app.add_option("--choose-pair", o.choose_pairs,
                   "Headless: tick this face pair A:F=B:G once the blocks are loaded");
    app.add_option("--choose-coplanar", o.choose_coplanar,
                   "Headless: then tick this co-planar link A:F=B:G (a neighbour pair of a "
                   "chosen pair)");
    app.add_flag("--choose-accepted", o.choose_accepted,
                 "Headless: tick the pairs accepted in the proposals (anascan blocks accept)");
    app.add_flag("--align", o.align, "Headless: then press Align and wait for it");
    app.add_flag("--accept-assembly", o.accept,
                 "Headless: then press \"Accept and save\" (only an ok alignment is saved)");
}

void add_options(CLI::App& app, anascan::field::FieldAppConfig& config) {
    app.add_option("--cloud", config.inputs.clouds, "PLY file(s) to show, one scan each")
        ->check(CLI::ExistingFile);
    app.add_option("--synthetic-points", config.inputs.synthetic_points,
                   "Add a synthetic stone of this many points (renderer measurements)");
    app.add_option("--synthetic-scans", config.inputs.synthetic_scans,
                   "Split the synthetic stone into this many scans")
        ->check(CLI::PositiveNumber);
    app.add_option("--screenshot", config.headless.screenshot_png,
                   "Write the last frame as PNG (default --frames 5)");
    app.add_option("--frames", config.headless.frames,
                   "Draw this many frames, then exit and print frame times (ms) on stderr")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--point-budget", config.view.point_budget,
                   "Points drawn per frame at most (0: adapt to --target-frame-ms)");
    app.add_option("--target-frame-ms", config.view.target_frame_ms,
                   "Frame time in ms the adaptive level of detail aims for")
        ->check(CLI::PositiveNumber);
    app.add_option("--point-size", config.view.point_size_px,
                   "Point size in pixels at full density (grows when thinned)")
        ->check(CLI::Range(1.0f, 16.0f));
    app.add_option("--orbit-per-frame", config.headless.orbit_px_per_frame,
                   "Turn the view by this many pixels of mouse motion every frame (to measure "
                   "frame times while the operator moves the view)");
    app.add_option("--width", config.view.width_px, "Window width, pixels (default: the screen's)")
        ->check(CLI::PositiveNumber);
    app.add_option("--height", config.view.height_px,
                   "Window height, pixels (default: the screen's)")
        ->check(CLI::PositiveNumber);
    app.add_option("--font-scale", config.view.font_scale, "Size of text and widgets (1 = small)")
        ->check(CLI::Range(0.5f, 4.0f));
    app.add_flag("--high-contrast", config.view.high_contrast,
                 "High-contrast theme (bright light)");
    const std::map<std::string, anascan::gui::ColorMode> modes{
        {"scan", anascan::gui::ColorMode::kByScan},
        {"quality", anascan::gui::ColorMode::kByQuality},
        {"coverage", anascan::gui::ColorMode::kByCoverage}};
    app.add_option("--color-by", config.view.color_mode, "Colour points by scan|quality|coverage")
        ->transform(CLI::CheckedTransformer(modes, CLI::ignore_case));
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "anascan-field: the field app of anascan (3D view of the scans, scan list, devices, "
        "status). Units are metres.",
        "anascan-field"};
    anascan::field::FieldAppConfig config;
    add_options(app, config);
    add_session_options(app, config);
    add_report_options(app, config);
    add_mesh_options(app, config);
    add_assembly_options(app, config.assembly);
    CLI11_PARSE(app, argc, argv);
    anascan::field::HeadlessConfig& headless = config.headless;
    if (headless.screenshot_png && headless.frames == 0) headless.frames = 5;
    if (headless.capture_views > 0 && (!config.session.dir || headless.frames == 0)) {
        std::fprintf(stderr,
                     "anascan-field: error: --capture-views needs --session and --frames "
                     "(or --screenshot)\n");
        return 2;
    }
    if (config.assembly.dir) {
        if (config.session.dir) {
            std::fprintf(stderr,
                         "anascan-field: error: --assembly and --session exclude each other\n");
            return 2;
        }
        return anascan::field::run_assembly_app(config);
    }
    return anascan::field::run_field_app(config);
}
