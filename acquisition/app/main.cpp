// anascan: the command line of the anascan scanning system.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdio>

#include "commands.hpp"

namespace {

void configure_logging(bool verbose, bool quiet) {
    auto logger = spdlog::stderr_color_mt("anascan");
    logger->set_pattern("%^%l%$: %v");
    logger->set_level(quiet ? spdlog::level::warn
                            : (verbose ? spdlog::level::debug : spdlog::level::info));
    spdlog::set_default_logger(logger);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "anascan: 3D documentation of stone blocks for anastylosis.\n"
        "Units are metres unless a file or option says otherwise.",
        "anascan"};
    app.require_subcommand(1);
    bool verbose = false;
    bool quiet = false;
    app.add_flag("-v,--verbose", verbose, "Print debug detail on stderr");
    app.add_flag("-q,--quiet", quiet, "Print only warnings and errors on stderr");
    bool accept_poor = false;
    app.add_flag("--accept-poor", accept_poor,
                 "Exit 0 even when a result is clearly unusable (default: exit code 3; "
                 "docs/exit-codes.md)");
    app.set_version_flag("--version", "anascan 0.1.0");
    anascan::cli::add_info_command(app);
    anascan::cli::add_convert_command(app);
    anascan::cli::add_assemble_command(app);
    anascan::cli::add_mesh_command(app);
    anascan::cli::add_eval_command(app);
    anascan::cli::add_register_command(app);
    anascan::cli::add_align_command(app);
    anascan::cli::add_sl_command(app);
    anascan::cli::add_devices_command(app);
    anascan::cli::add_sim_command(app);
    anascan::cli::add_demo_command(app);
    anascan::cli::add_capture_command(app);
    anascan::cli::add_coverage_command(app);
    anascan::cli::add_session_command(app);
    anascan::cli::add_campaign_command(app);
    anascan::cli::add_blocks_command(app);
    app.parse_complete_callback([&] {
        configure_logging(verbose, quiet);
        anascan::cli::set_accept_poor(accept_poor);
    });
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? anascan::cli::kExitOk : anascan::cli::kExitUsage;
    } catch (const anascan::cli::CommandFailed& e) {
        std::fprintf(stderr, "anascan: error: %s\n", e.what());
        return anascan::cli::kExitError;
    } catch (const anascan::cli::CommandInterrupted& e) {
        std::fprintf(stderr, "anascan: %s\n", e.what());
        return anascan::cli::kExitInterrupted;
    }
    return anascan::cli::result_exit_code();
}
