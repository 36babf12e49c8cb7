// anascan sl decode: a captured Gray-code stereo sequence -> point cloud (PLY).
#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <vector>

#include "anascan/drivers/structured_light/image_files.hpp"
#include "anascan/drivers/structured_light/stereo_decoder.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/io/ply.hpp"
#include "commands.hpp"
#include "point_files.hpp"

namespace anascan::cli {
namespace {

namespace sl = anascan::drivers::sl;
using Clock = std::chrono::steady_clock;

struct SlDecodeOptions {
    std::string calibration;
    std::string cam1_glob;
    std::string cam2_glob;
    std::string output;
    bool swap_cameras = false;
    double file_unit_m = 1e-3;
    int projector_width_px = 1280;
    int projector_height_px = 800;
    int phase_steps = 0;
    int phase_period_px = 16;
    bool projector_size_given = false;  ///< --projector-width/height on the command line.
    bool phase_given = false;           ///< --phase-steps/period on the command line.
    int min_contrast = 40;
    int min_bit_contrast = 5;
    double max_ray_gap_mm = 30.0;
    bool no_subpixel = false;
    int threads = 0;
};

sl::StereoDecodeConfig decode_config(const SlDecodeOptions& o) {
    sl::StereoDecodeConfig config;
    config.sequence.gray = {.projector_width_px = o.projector_width_px,
                            .projector_height_px = o.projector_height_px};
    if (o.phase_steps > 0)
        config.sequence.phase =
            sl::PhaseShiftLayout{.period_px = o.phase_period_px, .steps = o.phase_steps};
    config.gray = {.min_contrast = o.min_contrast,
                   .min_bit_contrast = o.min_bit_contrast,
                   .subpixel = !o.no_subpixel};
    config.triangulation.max_ray_gap_m = o.max_ray_gap_mm * 1e-3;
    return config;
}

/// The files of one camera, checked against the sequence length.
std::vector<std::filesystem::path> camera_files(const std::string& pattern, const char* name,
                                                std::size_t expected) {
    auto files = sl::glob_natural(pattern);
    if (!files) fail_command(files.error());
    if (files->size() != expected) {
        throw CommandFailed(std::string(name) + ": " + pattern + " matches " +
                            std::to_string(files->size()) + " files, the sequence has " +
                            std::to_string(expected) + " images");
    }
    return *files;
}

/// Loads both cameras' images in one parallel pass; progress on stderr.
std::vector<cv::Mat> load_all(const std::vector<std::filesystem::path>& files) {
    std::atomic<std::size_t> reported{0};
    const auto progress = [&](std::size_t done) {
        if (done % 11 == 0 || done == files.size()) {
            std::size_t r = reported.load();
            if (done > r && reported.compare_exchange_strong(r, done))
                spdlog::info("loaded {}/{} images", done, files.size());
        }
    };
    auto images = sl::load_grey_images(files, progress);
    if (!images) fail_command(images.error());
    return std::move(*images);
}

/// The pattern layout the calibration file records (the simulator writes it), where the
/// command line does not set it.
SlDecodeOptions with_recorded_layout(SlDecodeOptions o) {
    auto recorded = sl::load_pattern_layout(o.calibration);
    if (!recorded) fail_command(recorded.error());
    if (!*recorded) return o;
    const sl::RecordedPatternLayout& r = **recorded;
    if (!o.projector_size_given) {
        o.projector_width_px = r.projector_width_px;
        o.projector_height_px = r.projector_height_px;
    }
    if (!o.phase_given) {
        o.phase_steps = r.phase_steps;
        o.phase_period_px = r.phase_period_px > 0 ? r.phase_period_px : o.phase_period_px;
    }
    spdlog::info("pattern layout: projector {} x {} px, {} phase steps of period {} px{}",
                 o.projector_width_px, o.projector_height_px, o.phase_steps, o.phase_period_px,
                 o.projector_size_given && o.phase_given ? "" : " (from the calibration file)");
    return o;
}

// Clearly unusable results (docs/exit-codes.md): most matches missing each other, or none.
void check_decode_quality(const sl::StereoDecodeResult& r, const SlDecodeOptions& o) {
    if (2 * r.rejected_ray_gap > r.matched) {
        report_poor_result(
            fmt::format("{} of {} matches miss by more than {} mm: wrong camera order "
                        "(--swap-cameras), calibration unit or calibration?",
                        r.rejected_ray_gap, r.matched, o.max_ray_gap_mm));
    } else if (r.cloud.empty()) {
        report_poor_result(
            "no point triangulated: check the images, --min-contrast and the "
            "calibration");
    }
}

struct DecodeTimes {
    std::size_t image_count = 0;
    double load_s = 0.0, decode_s = 0.0, total_s = 0.0;
};

void print_decode_report(const sl::StereoDecodeResult& r, const SlDecodeOptions& o,
                         const DecodeTimes& t) {
    std::printf(
        "points: %zu (%.1f %% of %zu cam1 pixels; cam1 decoded %.1f %%, cam2 %.1f %%, "
        "matched %.1f %% of decoded)\n",
        r.cloud.size(), 100.0 * double(r.cloud.size()) / double(r.pixel_count), r.pixel_count,
        100.0 * double(r.cam1_valid) / double(r.pixel_count),
        100.0 * double(r.cam2_valid) / double(r.pixel_count),
        100.0 * double(r.matched) / double(std::max<std::size_t>(r.cam1_valid, 1)));
    std::printf("rejected: %zu ray gap > %.1f mm, %zu depth; median ray gap %.2f mm\n",
                r.rejected_ray_gap, o.max_ray_gap_mm, r.rejected_depth, r.median_ray_gap_m * 1e3);
    std::printf(
        "time: %.3f s (load %zu images %.3f s, decode %.3f s [codes %.3f s, matching "
        "%.3f s, triangulation %.3f s], write %.3f s)\n",
        t.total_s, t.image_count, t.load_s, t.decode_s, r.decode_s, r.match_s, r.triangulate_s,
        t.total_s - t.load_s - t.decode_s);
}

void run_sl_decode(const SlDecodeOptions& options) {
    const SlDecodeOptions o = with_recorded_layout(options);
    check_point_output(o.output);
    check_output_writable(o.output, "--out");
    const auto t0 = Clock::now();
    std::unique_ptr<tbb::global_control> thread_limit;
    if (o.threads > 0) {
        thread_limit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, std::size_t(o.threads));
    }
    const sl::StereoDecodeConfig config = decode_config(o);
    auto calibration = sl::load_stereo_calibration(
        o.calibration, {.swap_cameras = o.swap_cameras, .file_unit_m = o.file_unit_m});
    if (!calibration) fail_command(calibration.error());
    const std::size_t n = config.sequence.image_count();
    std::vector<std::filesystem::path> files = camera_files(o.cam1_glob, "cam1", n);
    const std::vector<std::filesystem::path> files2 = camera_files(o.cam2_glob, "cam2", n);
    files.insert(files.end(), files2.begin(), files2.end());
    const std::vector<cv::Mat> images = load_all(files);
    const double load_s = seconds_since(t0);
    spdlog::info("decoding and triangulating");
    const std::span<const cv::Mat> all(images);
    auto result = sl::decode_stereo(all.first(n), all.subspan(n), *calibration, config);
    if (!result) fail_command(result.error());
    const double decode_s = seconds_since(t0) - load_s;
    check_decode_quality(*result, o);
    write_points(o.output, result->cloud);
    const double total_s = seconds_since(t0);
    print_decode_report(*result, o, {files.size(), load_s, decode_s, total_s});
    std::printf("wrote %s (cam1 frame, metres)\n", o.output.c_str());
}

// The pattern layout and decoder tuning options; the layout's, to tell given from default.
struct LayoutOptions {
    CLI::Option *width, *height, *steps, *period;
};

LayoutOptions add_layout_options(CLI::App* cmd, SlDecodeOptions& o) {
    // Defaults, unless the calibration records the layout (proj_size, pattern_phase_*).
    LayoutOptions layout;
    layout.width = cmd->add_option("--projector-width", o.projector_width_px,
                                   "Projector width, px (default: the calibration's proj_size)")
                       ->capture_default_str();
    layout.height =
        cmd->add_option("--projector-height", o.projector_height_px, "Projector height, px")
            ->capture_default_str();
    layout.steps = cmd->add_option("--phase-steps", o.phase_steps,
                                   "Phase-shift images per axis after the Gray code (0: none; "
                                   "default: the calibration's pattern_phase_steps)")
                       ->capture_default_str();
    layout.period =
        cmd->add_option("--phase-period", o.phase_period_px, "Sinusoid period, projector px")
            ->capture_default_str();
    cmd->add_option("--min-contrast", o.min_contrast, "White - black, grey levels")
        ->capture_default_str();
    cmd->add_option("--min-bit-contrast", o.min_bit_contrast,
                    "|pattern - inverse| for a certain bit, grey levels")
        ->capture_default_str();
    cmd->add_option("--max-ray-gap", o.max_ray_gap_mm, "Largest ray gap, mm")
        ->capture_default_str();
    cmd->add_flag("--no-subpixel", o.no_subpixel, "Integer projector coordinates only");
    cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    return layout;
}

}  // namespace

void add_sl_command(CLI::App& app) {
    auto* sl_cmd = app.add_subcommand("sl", "Structured-light scanner tools");
    sl_cmd->require_subcommand(1);
    auto opts = std::make_shared<SlDecodeOptions>();
    auto* cmd = sl_cmd->add_subcommand(
        "decode",
        "Decode a captured Gray-code stereo sequence (OpenCV GrayCodePattern layout: column "
        "codes, row codes, each with its inverse, then white, black) into a PLY cloud in "
        "cam1's frame, metres. See docs/structured-light.md.");
    cmd->add_option("--calibration", opts->calibration, "OpenCV FileStorage stereo calibration")
        ->required();
    cmd->add_option("--cam1", opts->cam1_glob,
                    "Shell glob of cam1's images, JPEG or PNG (natural order)")
        ->required();
    cmd->add_option("--cam2", opts->cam2_glob,
                    "Shell glob of cam2's images, JPEG or PNG (natural order)")
        ->required();
    cmd->add_option("--out", opts->output, "Output .ply")->required();
    cmd->add_flag("--swap-cameras", opts->swap_cameras,
                  "The calibration's cam1 is the camera of the --cam2 images (GSoC statue data)");
    const std::map<std::string, double> units{{"mm", 1e-3}, {"cm", 1e-2}, {"m", 1.0}};
    cmd->add_option("--calibration-unit", opts->file_unit_m, "Unit of the calibration's T")
        ->transform(CLI::CheckedTransformer(units, CLI::ignore_case))
        ->default_str("mm");
    const LayoutOptions layout = add_layout_options(cmd, *opts);
    cmd->callback([opts, layout] {
        opts->projector_size_given = layout.width->count() > 0 || layout.height->count() > 0;
        opts->phase_given = layout.steps->count() > 0 || layout.period->count() > 0;
        run_sl_decode(*opts);
    });
}

}  // namespace anascan::cli
