#include "isolated_call.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <utility>

#include "unique_fd.hpp"

namespace anascan::drivers {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kHeaderBytes = sizeof(std::uint64_t);
/// A result larger than this is not a parser's answer: the read stops there.
constexpr std::size_t kMaxFrameBytes = std::size_t{1} << 24;
/// The child's exit statuses of its own (0: the result is written).
constexpr int kExitWriteFailed = 120;
constexpr int kExitWorkThrew = 121;

/// The one owner of a forked child: kills (SIGKILL) and reaps it unless it was reaped.
class ChildProcess {
public:
    explicit ChildProcess(pid_t pid) : pid_(pid) {}
    ~ChildProcess() {
        if (pid_ > 0) {
            kill();
            reap();
        }
    }
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    void kill() const { ::kill(pid_, SIGKILL); }
    /// Waits for the child's end: its wait status; empty when it cannot be known (the
    /// process ignores SIGCHLD, so the system reaped the child itself).
    std::optional<int> reap() {
        int status = 0;
        pid_t waited = -1;
        do waited = ::waitpid(pid_, &status, 0);
        while (waited < 0 && errno == EINTR);
        pid_ = -1;
        if (waited < 0) return std::nullopt;
        return status;
    }

private:
    pid_t pid_ = -1;
};

bool write_all(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t n = ::write(fd, bytes.data(), bytes.size());
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        bytes.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
}

/// The child: a crash ends it by its signal (not in a handler of the parent's, such as a
/// crash reporter or a sanitizer's), and it holds no descriptor of the parent's but its
/// pipe end, so it cannot keep another call's pipe open.
[[noreturn]] void run_child(int fd, const std::function<std::string()>& work) {
    for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS})
        std::signal(signal, SIG_DFL);
    if (fd > 3) ::close_range(3, static_cast<unsigned>(fd) - 1, 0);
    ::close_range(static_cast<unsigned>(fd) + 1, ~0U, 0);
    int status = kExitWorkThrew;
    try {
        status = write_all(fd, frame_message(work())) ? 0 : kExitWriteFailed;
    } catch (...) {
    }
    ::_exit(status);
}

/// The payload length a frame's header announces, once the header is there.
std::optional<std::uint64_t> announced_size(std::string_view bytes) {
    if (bytes.size() < kHeaderBytes) return std::nullopt;
    std::uint64_t size = 0;
    std::memcpy(&size, bytes.data(), kHeaderBytes);
    return size;
}

bool frame_is_complete(std::string_view bytes) {
    const auto size = announced_size(bytes);
    return size && bytes.size() - kHeaderBytes >= *size;
}

enum class Ending { kComplete, kClosed, kTimedOut, kFailed };

struct Received {
    Ending ending = Ending::kFailed;
    std::string bytes;
    int error_number = 0;  ///< errno of poll or read, with kFailed.
};

/// Waits until `fd` can be read (empty), the deadline passes (kTimedOut) or poll fails
/// (kFailed, with `error_number`); a signal's interruption is retried.
std::optional<Ending> wait_readable(int fd, Clock::time_point deadline, int& error_number) {
    for (;;) {
        const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
        if (left.count() <= 0) return Ending::kTimedOut;
        pollfd entry{.fd = fd, .events = POLLIN, .revents = 0};
        const int ready = ::poll(&entry, 1, static_cast<int>(left.count()));
        if (ready > 0) return std::nullopt;
        if (ready < 0 && errno != EINTR) {
            error_number = errno;
            return Ending::kFailed;
        }
    }
}

/// Reads the child's frame until it is complete, the child closes the pipe, or the deadline.
Received receive(int fd, Clock::time_point deadline) {
    Received received;
    std::array<char, 4096> chunk{};
    while (!frame_is_complete(received.bytes)) {
        if (received.bytes.size() > kMaxFrameBytes) {
            received.ending = Ending::kFailed;  // errno 0: oversized, not a read error
            return received;
        }
        if (const auto ended = wait_readable(fd, deadline, received.error_number)) {
            received.ending = *ended;
            return received;
        }
        const ssize_t n = ::read(fd, chunk.data(), chunk.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            received.error_number = errno;
            received.ending = Ending::kFailed;
            return received;
        }
        if (n == 0) {
            received.ending = Ending::kClosed;
            return received;
        }
        received.bytes.append(chunk.data(), static_cast<std::size_t>(n));
    }
    received.ending = Ending::kComplete;
    return received;
}

std::string seconds_text(std::chrono::milliseconds time) {
    std::ostringstream text;
    text << static_cast<double>(time.count()) / 1000.0 << " s";
    return text.str();
}

std::string signal_name(int signal) {
    const char* abbreviation = ::sigabbrev_np(signal);
    if (abbreviation == nullptr) return std::to_string(signal);
    return std::string("SIG") + abbreviation;
}

/// Why `bytes` is not a frame: " sent a truncated result (10 of 108 bytes)".
std::string unframed_text(std::string_view bytes) {
    const std::string got = std::to_string(bytes.size());
    const auto size = announced_size(bytes);
    if (!size) return " sent a truncated result (" + got + " bytes, no header)";
    if (bytes.size() - kHeaderBytes < *size)
        return " sent a truncated result (" + got + " of " + std::to_string(kHeaderBytes + *size) +
               " bytes)";
    return " sent a malformed result (" + got + " bytes)";
}

Error start_error(const IsolatedCallConfig& config, const char* call, int error_number) {
    return Error{ErrorCode::kIo, config.subject + ": " + config.worker + " could not be started (" +
                                     call + ": " + std::strerror(error_number) + ")"};
}

/// The call's result from what the child sent and how it ended (`status` empty: unknown).
Expected<std::string> outcome(const IsolatedCallConfig& config, const Received& received,
                              std::optional<int> status) {
    const std::string head = config.subject + ": " + config.worker;
    if (status && WIFSIGNALED(*status)) {
        return fail(ErrorCode::kFormat,
                    head + " crashed (signal " + signal_name(WTERMSIG(*status)) + ") on this file");
    }
    if (status && WIFEXITED(*status) && WEXITSTATUS(*status) != 0) {
        return fail(ErrorCode::kFormat,
                    head + " exited with status " + std::to_string(WEXITSTATUS(*status)));
    }
    if (received.ending == Ending::kFailed && received.error_number != 0) {
        return fail(ErrorCode::kIo, head + ": reading its result failed (" +
                                        std::strerror(received.error_number) + ")");
    }
    const auto payload = unframe_message(received.bytes);
    if (!payload) return fail(ErrorCode::kFormat, head + unframed_text(received.bytes));
    return std::string(*payload);
}

}  // namespace

std::string frame_message(std::string_view payload) {
    const std::uint64_t size = payload.size();
    std::string frame(kHeaderBytes, '\0');
    std::memcpy(frame.data(), &size, kHeaderBytes);
    frame.append(payload);
    return frame;
}

std::optional<std::string_view> unframe_message(std::string_view bytes) {
    const auto size = announced_size(bytes);
    if (!size || bytes.size() - kHeaderBytes != *size) return std::nullopt;
    return bytes.substr(kHeaderBytes);
}

Expected<std::string> call_isolated(const IsolatedCallConfig& config,
                                    const std::function<std::string()>& work) {
    std::array<int, 2> ends{};
    if (::pipe2(ends.data(), O_CLOEXEC) != 0) return fail(start_error(config, "pipe", errno));
    UniqueFd read_end(ends[0]), write_end(ends[1]);
    const Clock::time_point deadline = Clock::now() + config.time_limit;
    const pid_t pid = ::fork();
    if (pid < 0) return fail(start_error(config, "fork", errno));
    if (pid == 0) run_child(write_end.get(), work);
    ChildProcess child(pid);
    write_end.reset();  // The parent sees the end of the pipe when the child's end closes.
    const Received received = receive(read_end.get(), deadline);
    if (received.ending == Ending::kTimedOut) {  // `child` kills and reaps it on return.
        return fail(ErrorCode::kTimeout,
                    config.subject + ": " + config.worker + " did not finish within " +
                        seconds_text(config.time_limit) + " (malformed file?)");
    }
    if (received.ending == Ending::kFailed) child.kill();
    return outcome(config, received, child.reap());
}

}  // namespace anascan::drivers
