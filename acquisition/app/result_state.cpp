// How a command's result ends up in the exit code (docs/exit-codes.md).
#include <spdlog/spdlog.h>

#include "commands.hpp"

namespace anascan::cli {
namespace {

// The command line runs one command per process: its outcome is process state.
bool g_accept_poor = false;
bool g_poor = false;

}  // namespace

void set_accept_poor(bool accept) { g_accept_poor = accept; }

void report_poor_result(const std::string& what) {
    g_poor = true;
    spdlog::warn("poor result: {}", what);
    if (!g_accept_poor)
        spdlog::warn(
            "exit code {}: the result is written but clearly unusable "
            "(--accept-poor to exit 0 anyway; docs/exit-codes.md)",
            kExitPoor);
}

int result_exit_code() { return g_poor && !g_accept_poor ? kExitPoor : kExitOk; }

}  // namespace anascan::cli
