#pragma once
// Counter-based random numbers: a value is a pure function of (seed, counters), so results
// do not depend on the order or the thread in which samples are drawn. Not cryptographic.

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace anascan::sim::detail {

/// SplitMix64 finaliser (Steele et al. 2014): a well-mixed 64-bit hash.
inline std::uint64_t mix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

inline std::uint64_t hash3(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) {
    return mix64(mix64(mix64(seed) ^ a) ^ b);
}

/// Uniform in [0, 1) from a hash.
inline double unit_from_hash(std::uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

/// Standard normal sample from two hashes (Box-Muller).
inline double normal_from_hash(std::uint64_t h) {
    const double u1 = unit_from_hash(h) + 0x1.0p-54;  // (0, 1]: log stays finite.
    const double u2 = unit_from_hash(mix64(h));
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

/// Fast standard normal sample for image noise: one of 65536 fixed Box-Muller draws,
/// picked by the hash (a table lookup instead of a log and a cosine per pixel).
inline double fast_normal_from_hash(std::uint64_t h) {
    static const std::array<float, 65536> table = [] {
        std::array<float, 65536> t{};
        for (std::size_t i = 0; i < t.size(); ++i)
            t[i] = static_cast<float>(normal_from_hash(mix64(0xA5A5A5A5ull + i)));
        return t;
    }();
    return table[h >> 48];
}

/// Smooth 2-D value noise in [0, 1] with unit lattice spacing (bilinear with a smoothstep).
inline double value_noise(std::uint64_t seed, double x, double y) {
    const double fx = std::floor(x), fy = std::floor(y);
    const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
    auto corner = [&](std::int64_t dx, std::int64_t dy) {
        return unit_from_hash(
            hash3(seed, static_cast<std::uint64_t>(ix + dx), static_cast<std::uint64_t>(iy + dy)));
    };
    auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
    const double tx = smooth(x - fx), ty = smooth(y - fy);
    const double top = corner(0, 0) + tx * (corner(1, 0) - corner(0, 0));
    const double bottom = corner(0, 1) + tx * (corner(1, 1) - corner(0, 1));
    return top + ty * (bottom - top);
}

/// Fractal sum of `octaves` value-noise layers (each half the scale and amplitude), in [0, 1].
inline double fractal_noise(std::uint64_t seed, double x, double y, int octaves) {
    double sum = 0.0, weight = 0.0, amplitude = 1.0, scale = 1.0;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * value_noise(seed + static_cast<std::uint64_t>(o), x * scale, y * scale);
        weight += amplitude;
        amplitude *= 0.5;
        scale *= 2.0;
    }
    return sum / weight;
}

}  // namespace anascan::sim::detail
