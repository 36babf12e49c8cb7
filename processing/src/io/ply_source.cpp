#include "ply_source.hpp"

#include <array>
#include <cmath>

namespace anascan::io::ply_detail {
namespace {

struct IntegerRange {
    std::int64_t min;
    std::int64_t max;
};

IntegerRange range_of(PlyScalar type) {
    switch (type) {
        case PlyScalar::kInt8:
            return {INT8_MIN, INT8_MAX};
        case PlyScalar::kUint8:
            return {0, UINT8_MAX};
        case PlyScalar::kInt16:
            return {INT16_MIN, INT16_MAX};
        case PlyScalar::kUint16:
            return {0, UINT16_MAX};
        case PlyScalar::kInt32:
            return {INT32_MIN, INT32_MAX};
        default:
            return {0, UINT32_MAX};
    }
}

ReadStatus parse_integer(std::string_view token, PlyScalar type, double& value) {
    std::int64_t number = 0;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, number);
    if (ec == std::errc::result_out_of_range) return ReadStatus::kOutOfRange;
    if (ec != std::errc() || ptr != end) return ReadStatus::kNotANumber;
    const IntegerRange range = range_of(type);
    if (number < range.min || number > range.max) return ReadStatus::kOutOfRange;
    value = static_cast<double>(number);
    return ReadStatus::kOk;
}

template <class T>
std::errc parse_real(std::string_view token, T& number) {
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, number);
    if (ec == std::errc() && ptr != end) return std::errc::invalid_argument;
    return ec;
}

// Float properties parse as float directly (no double rounding); a value outside float's
// range (1e-50, 1e300) becomes what a float conversion gives: zero or infinity.
ReadStatus parse_float(std::string_view token, double& value) {
    float number = 0.0f;
    const std::errc ec = parse_real(token, number);
    if (ec == std::errc()) {
        value = number;
        return ReadStatus::kOk;
    }
    if (ec != std::errc::result_out_of_range) return ReadStatus::kNotANumber;
    double wide = 0.0;
    if (parse_real(token, wide) != std::errc()) return ReadStatus::kOutOfRange;
    constexpr double kMax = std::numeric_limits<float>::max();
    value = std::abs(wide) > kMax ? std::copysign(HUGE_VAL, wide) : static_cast<float>(wide);
    return ReadStatus::kOk;
}

ReadStatus parse_number(std::string_view token, PlyScalar type, double& value) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    if (is_integer(type)) return parse_integer(token, type, value);
    if (type == PlyScalar::kFloat32) return parse_float(token, value);
    const std::errc ec = parse_real(token, value);
    if (ec == std::errc::result_out_of_range) return ReadStatus::kOutOfRange;
    return ec == std::errc() ? ReadStatus::kOk : ReadStatus::kNotANumber;
}

}  // namespace

bool AsciiSource::begin_record() {
    for (;;) {
        skip_blanks(size_);
        if (pos_ >= size_) return false;
        if (data_[pos_] != '\n') break;
        ++pos_;
        ++line_;
    }
    const void* newline = std::memchr(data_ + pos_, '\n', size_ - pos_);
    line_end_ = newline != nullptr
                    ? static_cast<std::size_t>(static_cast<const char*>(newline) - data_)
                    : size_;
    return true;
}

ReadStatus AsciiSource::read(PlyScalar type, double& value) {
    skip_blanks(line_end_);
    const std::size_t start = pos_;
    while (pos_ < line_end_ && !is_blank(data_[pos_])) ++pos_;
    token_ = std::string_view(data_ + start, pos_ - start);
    if (token_.empty()) return ReadStatus::kEnd;
    return parse_number(token_, type, value);
}

ReadStatus AsciiSource::end_record() {
    skip_blanks(line_end_);
    if (pos_ < line_end_) {
        const std::size_t start = pos_;
        while (pos_ < line_end_ && !is_blank(data_[pos_])) ++pos_;
        token_ = std::string_view(data_ + start, pos_ - start);
        return ReadStatus::kExtra;
    }
    if (pos_ < size_) {
        ++pos_;  // the newline
        ++line_;
    }
    return ReadStatus::kOk;
}

bool AsciiSource::at_end() {
    for (; pos_ < size_; ++pos_) {
        if (data_[pos_] == '\n') {
            ++line_;
        } else if (!is_blank(data_[pos_])) {
            return false;
        }
    }
    return true;
}

}  // namespace anascan::io::ply_detail
