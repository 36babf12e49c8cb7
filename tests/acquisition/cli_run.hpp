#pragma once
// Runs the `anascan` executable (ANASCAN_CLI) as a user would.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace anascan::test {

struct CliRun {
    int exit_code = -1;
    std::string output;  // stdout and stderr together
};

inline CliRun run_cli(const std::string& args) {
    CliRun run;
    const std::string command = std::string(ANASCAN_CLI) + " " + args + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) return run;
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) run.output += buffer.data();
    const int status = ::pclose(pipe);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

}  // namespace anascan::test
