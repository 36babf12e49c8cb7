#pragma once
// Runs `anascan ARGS` (ANASCAN_CLI) and SIGKILLs it at a chosen moment: the kill tests of the
// commands that write (capture, session register, session export, campaign register).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "../cli_runner.hpp"

namespace anascan::testing_util {

struct KilledRun {
    std::set<std::int64_t> acknowledged;  ///< Seqs printed as saved before the kill.
    bool exited_before_kill = false;
};

/// Starts `PROGRAM ARGS`, reads its stdout until `after` (counted from the start, or with
/// `after_first_output` from its first output: a loaded machine may take longer than the
/// longest `after` to start), then SIGKILLs it. "saved scan N" lines are acknowledgements.
inline KilledRun run_program_and_kill(const char* program, const std::vector<std::string>& args,
                                      std::chrono::milliseconds after, bool after_first_output) {
    int out[2];
    EXPECT_EQ(::pipe(out), 0);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::dup2(out[1], STDOUT_FILENO);
        const int null = ::open("/dev/null", O_WRONLY);
        ::dup2(null, STDERR_FILENO);
        ::close(out[0]);
        std::vector<char*> argv{const_cast<char*>(program)};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(program, argv.data());
        ::_exit(127);
    }
    ::close(out[1]);
    KilledRun run;
    std::string text;
    auto deadline = std::chrono::steady_clock::now() +
                    (after_first_output ? std::chrono::milliseconds(600000) : after);
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) break;
        pollfd p{.fd = out[0], .events = POLLIN, .revents = 0};
        if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
        char buffer[4096];
        const ssize_t n = ::read(out[0], buffer, sizeof(buffer));
        if (n <= 0) {
            run.exited_before_kill = true;
            break;
        }
        if (after_first_output && text.empty()) deadline = std::chrono::steady_clock::now() + after;
        text.append(buffer, static_cast<std::size_t>(n));
    }
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ::close(out[0]);
    static const std::regex saved(R"(saved scan (\d+) )");
    // Only complete lines count: the line is printed after the acknowledgement.
    const std::string complete = text.substr(0, text.rfind('\n') + 1);
    for (std::sregex_iterator it(complete.begin(), complete.end(), saved), end; it != end; ++it)
        run.acknowledged.insert(std::stoll((*it)[1]));
    return run;
}

/// `anascan ARGS`, killed as `run_program_and_kill` does.
inline KilledRun run_and_kill(const std::vector<std::string>& args, std::chrono::milliseconds after,
                              bool after_first_output) {
    return run_program_and_kill(ANASCAN_CLI, args, after, after_first_output);
}

/// Kills per command: ANASCAN_WRITE_KILLS (5 by default; the soak scripts ask for more).
inline int kills_per_command() {
    const char* env = std::getenv("ANASCAN_WRITE_KILLS");
    return env != nullptr ? std::max(1, std::atoi(env)) : 5;
}

/// Kill moments spread over the whole unkilled run (and a little past its end).
inline std::vector<std::chrono::milliseconds> kill_moments(std::chrono::milliseconds run_time) {
    std::mt19937_64 rng(20261201);
    std::uniform_int_distribution<std::int64_t> ms(0, run_time.count() * 11 / 10);
    std::vector<std::chrono::milliseconds> moments;
    for (int k = 0; k < kills_per_command(); ++k) moments.emplace_back(ms(rng));
    return moments;
}

/// Temporary siblings (".NAME.tmpNNN") left in a folder by killed writers.
inline int temporaries_in(const std::filesystem::path& dir) {
    int n = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with('.') && name.find(".tmp") != std::string::npos) ++n;
    }
    return n;
}

/// Runs `anascan ARGS` to its end; returns its wall time.
inline std::chrono::milliseconds run_to_end(const std::string& args) {
    const auto start = std::chrono::steady_clock::now();
    const auto run = run_cli(args);
    EXPECT_EQ(run.exit_code, 0) << args << ":\n" << run.output;
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() -
                                                                 start);
}

}  // namespace anascan::testing_util
