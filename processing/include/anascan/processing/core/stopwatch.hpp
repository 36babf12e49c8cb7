#pragma once
/// \file
/// Elapsed time for the timing figures of results and reports: one definition, in seconds.

#include <chrono>

namespace anascan {

/// Seconds from `start` until now, on the clock of `start` (steady for durations, the
/// system clock for ages of stored events).
template <class Clock, class Duration>
double seconds_since(std::chrono::time_point<Clock, Duration> start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// A steady-clock stopwatch started at construction.
class Stopwatch {
public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    /// Seconds since construction or the last `restart`.
    double seconds() const { return seconds_since(start_); }
    void restart() { start_ = std::chrono::steady_clock::now(); }
    /// Seconds of the lap that ends now; the next lap starts now.
    double lap() {
        const auto now = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(now - start_).count();
        start_ = now;
        return s;
    }

private:
    std::chrono::steady_clock::time_point start_;
};

/// Adds the seconds a scope took to `total_s` when the scope ends: one named stage of a
/// pipeline is `{ ScopedTimer timer(result.timings.stage_s); run_stage(); }`.
class ScopedTimer {
public:
    explicit ScopedTimer(double& total_s) : total_s_(total_s) {}
    ~ScopedTimer() { total_s_ += watch_.seconds(); }
    ScopedTimer(const ScopedTimer&) = delete;
    ScopedTimer& operator=(const ScopedTimer&) = delete;

private:
    double& total_s_;
    Stopwatch watch_;
};

}  // namespace anascan
