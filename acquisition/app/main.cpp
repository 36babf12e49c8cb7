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
    app.set_version_flag("--version", "anascan 0.1.0");
    anascan::cli::add_info_command(app);
    anascan::cli::add_convert_command(app);
    anascan::cli::add_assemble_command(app);
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
    anascan::cli::add_blocks_command(app);
    app.parse_complete_callback([&] { configure_logging(verbose, quiet); });
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const anascan::cli::CommandFailed& e) {
        std::fprintf(stderr, "anascan: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
