#pragma once
// Sub-commands of the `anascan` command line. Each registers itself on the app; its
// callback prints results on stdout, progress on stderr, and throws CommandFailed with a
// message for the user on error (main turns it into exit code 1). A result that is written
// but clearly unusable is reported with report_poor_result (exit code 3). The exit codes
// and result states are in docs/exit-codes.md.

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

#include "anascan/processing/core/error.hpp"

namespace anascan::cli {

struct CommandFailed : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Throws CommandFailed carrying the error's message.
[[noreturn]] inline void fail_command(const Error& error) { throw CommandFailed(error.message); }

/// Exit codes of the command line (docs/exit-codes.md).
enum ExitCode : int {
    kExitOk = 0,
    kExitError = 1,         ///< CommandFailed: bad input, device, output; nothing usable.
    kExitUsage = 2,         ///< The command line itself is wrong.
    kExitPoor = 3,          ///< Outputs written, but the result is clearly unusable.
    kExitInterrupted = 130  ///< Stopped cleanly by Ctrl-C (SIGINT).
};

/// The command ran to the end and wrote its outputs, but the result is clearly unusable:
/// warns with `what` (say why and what to try); the process exits with kExitPoor unless
/// --accept-poor was given.
void report_poor_result(const std::string& what);
/// --accept-poor: a poor result exits 0 (the warning is still printed).
void set_accept_poor(bool accept);
/// kExitPoor after report_poor_result (unless accepted), else kExitOk.
int result_exit_code();

/// A command stopped by the operator (Ctrl-C) after leaving everything consistent; main
/// prints the message and exits with kExitInterrupted.
struct CommandInterrupted : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void add_info_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_assemble_command(CLI::App& app);
/// `mesh POSES.conf --out MESH`: the fragment model of scans placed by a .conf.
void add_mesh_command(CLI::App& app);
/// `mesh eval MESH --truth TRUE.ply`: a fragment model against the true surface.
void add_mesh_eval_command(CLI::App& mesh);
void add_demo_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_register_command(CLI::App& app);
void add_align_command(CLI::App& app);
/// `sl decode`: structured-light stereo images -> point cloud.
void add_sl_command(CLI::App& app);
/// `devices`: connected and named devices with their capabilities (text or --json).
void add_devices_command(CLI::App& app);
/// `capture`: a scanning session (simulated operator with sim: devices).
void add_capture_command(CLI::App& app);
/// `coverage DIR`: the stone's observed fraction and holes from a session.
void add_coverage_command(CLI::App& app);
/// Hidden `sim move-scans`: randomly moved copies of the scans of a .conf (for tests).
void add_sim_command(CLI::App& app);
/// `sim list-scenes`, `sim export-scene` (registered by add_sim_command on its group).
void add_sim_scene_commands(CLI::App& sim);
/// `sim tof-scan`, `sim sl-capture`: simulated scanners on the named scenes.
void add_sim_scanner_commands(CLI::App& sim);
/// `sim list-monuments`, `sim export-monument`: the simulated monument with its truth.
void add_sim_monument_commands(CLI::App& sim);
/// `blocks features|match|accept|reject|eval`: block features and neighbour proposals.
void add_blocks_command(CLI::App& app);
/// `blocks match|accept|reject` (registered by add_blocks_command on its group).
void add_blocks_match_commands(CLI::App& blocks);
/// `blocks eval` (registered by add_blocks_command on its group).
void add_blocks_eval_command(CLI::App& blocks);
/// `blocks assemble` (registered by add_blocks_command on its group).
void add_blocks_assemble_command(CLI::App& blocks);
/// `blocks eval ASSEMBLY/`: an assembly folder against the truth (cmd_blocks_eval.cpp).
void run_assembly_eval(const std::string& dir, const std::string& truth, bool as_json);
/// `session info|check|export|exclude|note|turned-over`: a capture session folder.
void add_session_command(CLI::App& app);
/// `campaign init|register|status|export`: many unordered scans of many stones.
void add_campaign_command(CLI::App& app);
/// `sim campaign`: a simulated campaign with its truth (registered on the sim group).
void add_sim_campaign_command(CLI::App& sim);

}  // namespace anascan::cli
