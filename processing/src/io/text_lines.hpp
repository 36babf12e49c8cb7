#pragma once
/// \file
/// Private helpers of the text parsers (XYZ, PTS, PTX, .conf, .xf): a line reader that
/// counts lines, field splitting, strict number parsing with std::from_chars, and errors
/// worded "source: line N: what was wrong".

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "anascan/processing/core/expected.hpp"

namespace anascan::io::text {

/// Field separators of formats that allow only blanks (PTX, .conf, .xf).
inline constexpr std::string_view kBlanks = " \t\r\v\f";
/// Field separators of XYZ and PTS: blanks or commas.
inline constexpr std::string_view kBlanksAndCommas = " \t\r\v\f,";

/// Walks text line by line (LF or CRLF endings), skipping blank lines and, when asked,
/// comments (`#` or `//` up to the end of the line). Not thread-safe; cheap to copy.
class LineReader {
public:
    explicit LineReader(std::span<const char> bytes, bool strip_comments);

    /// Advances to the next line with content; false at the end of the text.
    bool next();
    /// The current line without its ending, comment and surrounding blanks.
    std::string_view line() const { return line_; }
    /// 1-based number of the current line; at the end, the number of the last line (>= 1).
    int line_number() const { return line_number_ < 1 ? 1 : line_number_; }
    /// Bytes after the current line (to bound sizes announced by headers).
    std::size_t remaining_bytes() const { return text_.size() - pos_; }

private:
    std::string_view text_;
    std::size_t pos_ = 0;
    int line_number_ = 0;
    bool strip_comments_ = true;
    std::string_view line_;
};

/// The fields of one line. Keeps the first kMax; `count` is the true number of fields.
struct Fields {
    static constexpr std::size_t kMax = 16;
    std::array<std::string_view, kMax> items{};
    std::size_t count = 0;

    std::string_view operator[](std::size_t i) const { return items[i]; }
};

/// Splits `line` on any run of the characters in `separators`.
Fields split_fields(std::string_view line, std::string_view separators);

/// Where a line is, for error messages.
struct LineRef {
    std::string_view source;
    int line = 0;
};

/// An error "source: line N: what".
Unexpected<Error> line_error(ErrorCode code, LineRef where, std::string_view what);

/// Parses a whole token as a finite double (a leading '+' is allowed); errors say which
/// field (1-based) held what.
Expected<double> parse_double(std::string_view token, std::size_t field, LineRef where);

/// Parses fields [first, first + out.size()) of `fields` as finite doubles.
Expected<void> parse_doubles(const Fields& fields, std::size_t first, std::span<double> out,
                             LineRef where);

/// Parses a whole token as an unsigned integer no larger than `max`.
Expected<std::uint64_t> parse_count(std::string_view token, std::uint64_t max, LineRef where);

/// True when `token` is a plain decimal integer in 0..255 (a colour channel).
bool is_color_channel(std::string_view token);

/// Parses a colour channel 0..255; errors name the field.
Expected<std::uint8_t> parse_channel(std::string_view token, std::size_t field, LineRef where);

/// Converts a double to float, failing when it does not fit.
Expected<float> to_float(double value, std::size_t field, LineRef where);

/// Origin for a cloud whose first point is `first_point_m`: zero, unless the point lies
/// further than 1 km from 0 (site coordinates); then that point rounded to whole metres, so
/// float positions relative to it keep sub-millimetre precision.
Eigen::Vector3d origin_for(const Eigen::Vector3d& first_point_m);

/// `value` printed with round-trip precision (%.17g).
std::string format_exact(double value);

}  // namespace anascan::io::text
