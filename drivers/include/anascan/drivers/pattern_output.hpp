#pragma once
/// \file
/// Where a structured-light scanner's patterns go: a projector (the GLFW window of
/// projector_output.hpp, or a simulated one). Patterns are loaded once, then shown by
/// index; show() returns when the pattern is whole on the output, with that time, so that
/// the cameras' frames can be told apart: a frame exposed before it is stale.

#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

/// One pattern: 8-bit grey, row-major, row 0 at the top, exactly the output's size.
struct Pattern {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> grey;
};

/// Not thread-safe: one thread loads and shows.
class PatternOutput {
public:
    virtual ~PatternOutput() = default;
    PatternOutput() = default;
    PatternOutput(const PatternOutput&) = delete;
    PatternOutput& operator=(const PatternOutput&) = delete;

    /// Names the output in messages ("projector (monitor 1)", "sim:projector").
    virtual std::string name() const = 0;
    /// Output size in pixels: every pattern must have it.
    virtual int width_px() const = 0;
    virtual int height_px() const = 0;
    /// Keeps the sequence for show(); kInvalidArgument (naming the pattern) for a pattern
    /// of the wrong size.
    virtual Expected<void> load(std::span<const Pattern> patterns) = 0;
    /// Shows loaded pattern `index` and returns once it is whole on the output: the time
    /// from which it is shown, host steady clock (the clock of Frame::timestamp_ns).
    /// kInvalidArgument for an index out of range, kDisconnected when the output went away.
    virtual Expected<std::chrono::nanoseconds> show(std::size_t index) = 0;
};

/// Checks every pattern against the output size; `output` names it in the message.
Expected<void> check_patterns(std::span<const Pattern> patterns, int width_px, int height_px,
                              const std::string& output);

/// kInvalidArgument naming `output` when `index` is not below `loaded`.
Expected<void> check_pattern_index(std::size_t index, std::size_t loaded,
                                   const std::string& output);

/// Now on the host steady clock (the clock of show() and Frame::timestamp_ns).
inline std::chrono::nanoseconds steady_now() {
    return std::chrono::steady_clock::now().time_since_epoch();
}

}  // namespace anascan::drivers
