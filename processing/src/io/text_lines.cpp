#include "text_lines.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace anascan::io::text {
namespace {

constexpr std::size_t kMaxQuotedToken = 32;
constexpr double kRecentreBeyond_m = 1000.0;

std::string_view trim(std::string_view s) {
    const std::size_t first = s.find_first_not_of(kBlanks);
    if (first == std::string_view::npos) return {};
    const std::size_t last = s.find_last_not_of(kBlanks);
    return s.substr(first, last - first + 1);
}

std::string_view strip_comment(std::string_view s) {
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '#') return s.substr(0, i);
        if (s[i] == '/' && i + 1 < s.size() && s[i + 1] == '/') return s.substr(0, i);
    }
    return s;
}

// The token quoted for a message, shortened so that a binary blob cannot flood it.
std::string quoted(std::string_view token) {
    std::string out = "'";
    for (const char c : token.substr(0, kMaxQuotedToken)) {
        const bool printable = c >= 0x20 && c < 0x7f;
        out += printable ? c : '?';
    }
    if (token.size() > kMaxQuotedToken) out += "...";
    return out + "'";
}

std::string field_text(std::size_t field, std::string_view token) {
    return "field " + std::to_string(field) + " " + quoted(token);
}

}  // namespace

LineReader::LineReader(std::span<const char> bytes, bool strip_comments)
    : text_(bytes.data(), bytes.size()), strip_comments_(strip_comments) {}

bool LineReader::next() {
    while (pos_ < text_.size()) {
        const std::size_t end = text_.find('\n', pos_);
        const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
        std::string_view raw = text_.substr(pos_, stop - pos_);
        pos_ = end == std::string_view::npos ? text_.size() : end + 1;
        ++line_number_;
        if (strip_comments_) raw = strip_comment(raw);
        line_ = trim(raw);
        if (!line_.empty()) return true;
    }
    line_ = {};
    return false;
}

Fields split_fields(std::string_view line, std::string_view separators) {
    Fields fields;
    std::size_t pos = line.find_first_not_of(separators);
    while (pos != std::string_view::npos) {
        const std::size_t end = line.find_first_of(separators, pos);
        const std::size_t stop = end == std::string_view::npos ? line.size() : end;
        if (fields.count < Fields::kMax) fields.items[fields.count] = line.substr(pos, stop - pos);
        ++fields.count;
        pos = end == std::string_view::npos ? end : line.find_first_not_of(separators, end);
    }
    return fields;
}

Unexpected<Error> line_error(ErrorCode code, LineRef where, std::string_view what) {
    std::string message(where.source);
    message += ": line " + std::to_string(where.line) + ": ";
    message += what;
    return fail(code, std::move(message));
}

Expected<double> parse_double(std::string_view token, std::size_t field, LineRef where) {
    std::string_view digits = token;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    double value = 0.0;
    const char* end = digits.data() + digits.size();
    const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
    if (ec == std::errc::result_out_of_range) {
        return line_error(ErrorCode::kFormat, where, field_text(field, token) + " is out of range");
    }
    const bool plus_minus = token.size() > digits.size() && !digits.empty() && digits[0] == '-';
    if (ec != std::errc() || ptr != end || digits.empty() || plus_minus) {
        return line_error(ErrorCode::kFormat, where, field_text(field, token) + " is not a number");
    }
    if (!std::isfinite(value)) {
        return line_error(ErrorCode::kFormat, where, field_text(field, token) + " is not finite");
    }
    return value;
}

Expected<void> parse_doubles(const Fields& fields, std::size_t first, std::span<double> out,
                             LineRef where) {
    for (std::size_t i = 0; i < out.size(); ++i) {
        const Expected<double> value = parse_double(fields[first + i], first + i + 1, where);
        if (!value) return fail(value.error());
        out[i] = *value;
    }
    return {};
}

Expected<std::uint64_t> parse_count(std::string_view token, std::uint64_t max, LineRef where) {
    std::uint64_t value = 0;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, value);
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && ptr == end && value > max)) {
        return line_error(ErrorCode::kFormat, where,
                          "count " + quoted(token) + " is larger than " + std::to_string(max));
    }
    if (ec != std::errc() || ptr != end) {
        return line_error(ErrorCode::kFormat, where,
                          "expected a whole number, found " + quoted(token));
    }
    return value;
}

bool is_color_channel(std::string_view token) {
    unsigned value = 0;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, value);
    return ec == std::errc() && ptr == end && value <= 255;
}

Expected<std::uint8_t> parse_channel(std::string_view token, std::size_t field, LineRef where) {
    if (!is_color_channel(token)) {
        return line_error(ErrorCode::kFormat, where,
                          field_text(field, token) + " is not a colour value 0-255");
    }
    unsigned value = 0;
    std::from_chars(token.data(), token.data() + token.size(), value);
    return static_cast<std::uint8_t>(value);
}

Expected<float> to_float(double value, std::size_t field, LineRef where) {
    if (std::abs(value) > static_cast<double>(std::numeric_limits<float>::max())) {
        return line_error(ErrorCode::kFormat, where,
                          "field " + std::to_string(field) + " is too large for a float");
    }
    return static_cast<float>(value);
}

Eigen::Vector3d origin_for(const Eigen::Vector3d& first_point_m) {
    if (first_point_m.cwiseAbs().maxCoeff() <= kRecentreBeyond_m) return Eigen::Vector3d::Zero();
    return first_point_m.array().round().matrix();
}

std::string format_exact(double value) {
    char buffer[32];
    const int n = std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return std::string(buffer, static_cast<std::size_t>(n));
}

}  // namespace anascan::io::text
