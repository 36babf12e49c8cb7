#pragma once
// Runs the `anascan` executable (ANASCAN_CLI) as a user would; a fixture with a scratch folder.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace anascan::testing_util {

struct CliRun {
    int exit_code = -1;
    std::string output;  // stdout and stderr together
};

/// Runs a shell command line; its stdout (and whatever it redirects there) is the output.
inline CliRun run_shell(const std::string& command) {
    CliRun run;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) return run;
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) run.output += buffer.data();
    const int status = ::pclose(pipe);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

/// `anascan ARGS`, stdout and stderr together.
inline CliRun run_cli(const std::string& args) {
    return run_shell(std::string(ANASCAN_CLI) + " " + args + " 2>&1");
}

/// `anascan ARGS`, stdout only (e.g. JSON), stderr dropped.
inline CliRun run_cli_stdout(const std::string& args) {
    return run_shell(std::string(ANASCAN_CLI) + " " + args + " 2>/dev/null");
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        namespace fs = std::filesystem;
        dir_ = fs::path(::testing::TempDir()) / ("cli-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path dir_;
};

}  // namespace anascan::testing_util
