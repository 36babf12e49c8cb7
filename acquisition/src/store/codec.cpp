#include "store/codec.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace anascan::acquisition::codec {
namespace {

template <std::size_t N>
std::optional<std::array<double, N>> parse_numbers(std::string_view text) {
    std::array<double, N> values{};
    const char* p = text.data();
    const char* end = text.data() + text.size();
    for (double& v : values) {
        while (p < end && *p == ' ') ++p;
        const auto [next, ec] = std::from_chars(p, end, v);
        if (ec != std::errc() || !std::isfinite(v)) return std::nullopt;
        p = next;
    }
    while (p < end && *p == ' ') ++p;
    if (p != end) return std::nullopt;
    return values;
}

std::string format_numbers(const double* values, std::size_t n) {
    std::string text;
    for (std::size_t i = 0; i < n; ++i) {
        std::array<char, 32> buffer{};
        std::snprintf(buffer.data(), buffer.size(), "%.17g", values[i]);
        if (i > 0) text += ' ';
        text += buffer.data();
    }
    return text;
}

}  // namespace

std::string pose_to_text(const Pose& T) {
    std::array<double, 16> values{};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) values[static_cast<std::size_t>(4 * r + c)] = T.matrix()(r, c);
    return format_numbers(values.data(), values.size());
}

std::optional<std::string> pose_to_text(const std::optional<Pose>& T) {
    if (!T) return std::nullopt;
    return pose_to_text(*T);
}

std::optional<Pose> pose_from_text(std::string_view text) {
    const auto values = parse_numbers<16>(text);
    if (!values) return std::nullopt;
    Pose T = Pose::Identity();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
            T.matrix()(r, c) = (*values)[static_cast<std::size_t>(4 * r + c)];
    return T;
}

std::optional<std::string> vector_to_text(const std::optional<Eigen::Vector3d>& v) {
    if (!v) return std::nullopt;
    return format_numbers(v->data(), 3);
}

std::optional<Eigen::Vector3d> vector_from_text(std::string_view text) {
    const auto values = parse_numbers<3>(text);
    if (!values) return std::nullopt;
    return Eigen::Vector3d((*values)[0], (*values)[1], (*values)[2]);
}

std::int64_t to_ns(TimePoint t) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

TimePoint from_ns(std::int64_t ns) {
    return TimePoint(std::chrono::duration_cast<TimePoint::duration>(std::chrono::nanoseconds(ns)));
}

DeviceKind device_kind_from_string(std::string_view name) {
    for (DeviceKind k :
         {DeviceKind::kStructuredLight, DeviceKind::kTimeOfFlight, DeviceKind::kImported}) {
        if (name == to_string(k)) return k;
    }
    return DeviceKind::kUnknown;
}

}  // namespace anascan::acquisition::codec
