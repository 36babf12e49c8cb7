#pragma once
// Private to processing/src/io: value-by-value readers of a PLY body, one for binary (either
// byte order) and one for ASCII. Both never read outside their buffer and say where they
// are ("byte N" / "line N") for error messages. Templates instead of virtual calls: the
// element readers are instantiated once per source type.

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <string_view>

#include "ply_header.hpp"

namespace anascan::io::ply_detail {

/// Result of reading one value.
enum class ReadStatus {
    kOk,
    kEnd,         ///< Binary: the data ends. ASCII: the line ends (too few values).
    kNotANumber,  ///< ASCII: the token is not a number of the property's type.
    kOutOfRange,  ///< ASCII: a number outside the property's type.
    kExtra,       ///< ASCII: the line has more values than the element's properties.
};

template <class T>
T byte_swapped(T value) {
    if constexpr (sizeof(T) == 1) {
        return value;
    } else {
        unsigned char bytes[sizeof(T)];
        std::memcpy(bytes, &value, sizeof(T));
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
            const unsigned char tmp = bytes[i];
            bytes[i] = bytes[sizeof(T) - 1 - i];
            bytes[sizeof(T) - 1 - i] = tmp;
        }
        std::memcpy(&value, bytes, sizeof(T));
        return value;
    }
}

/// Loads a T stored at `p` (any alignment), swapping bytes when the file's order differs.
template <class T, bool kSwap>
T load(const char* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));
    if constexpr (kSwap) value = byte_swapped(value);
    return value;
}

/// Loads one value of `type` as a double (exact for every PLY type).
template <bool kSwap>
double load_scalar(const char* p, PlyScalar type) {
    switch (type) {
        case PlyScalar::kInt8:
            return load<std::int8_t, kSwap>(p);
        case PlyScalar::kUint8:
            return load<std::uint8_t, kSwap>(p);
        case PlyScalar::kInt16:
            return load<std::int16_t, kSwap>(p);
        case PlyScalar::kUint16:
            return load<std::uint16_t, kSwap>(p);
        case PlyScalar::kInt32:
            return load<std::int32_t, kSwap>(p);
        case PlyScalar::kUint32:
            return load<std::uint32_t, kSwap>(p);
        case PlyScalar::kFloat32:
            return load<float, kSwap>(p);
        case PlyScalar::kFloat64:
            return load<double, kSwap>(p);
    }
    return 0.0;
}

/// Reads a binary body; kSwap when the file's byte order is not the machine's.
template <bool kSwap>
class BinarySource {
public:
    static constexpr bool kBinary = true;
    static constexpr bool kSwapped = kSwap;

    BinarySource(std::span<const char> bytes, std::size_t position)
        : data_(bytes.data()), size_(bytes.size()), pos_(position), mark_(position) {}

    bool begin_record() {
        mark_ = pos_;
        return pos_ < size_;
    }
    ReadStatus read(PlyScalar type, double& value) {
        mark_ = pos_;
        const std::size_t n = scalar_size(type);
        if (size_ - pos_ < n) return ReadStatus::kEnd;
        value = load_scalar<kSwap>(data_ + pos_, type);
        pos_ += n;
        return ReadStatus::kOk;
    }
    ReadStatus end_record() { return ReadStatus::kOk; }
    /// True when nothing but (ASCII) white space follows the last element.
    bool at_end() {
        mark_ = pos_;
        return pos_ == size_;
    }
    std::string location() const { return "byte " + std::to_string(mark_); }
    std::size_t remaining() const { return size_ - pos_; }
    /// Fewest bytes a value of `type` can take, to bound counts by the data left.
    static std::size_t min_value_bytes(PlyScalar type) { return scalar_size(type); }
    std::string_view last_token() const { return {}; }

    const char* data() const { return data_; }
    std::size_t position() const { return pos_; }
    void skip(std::size_t n) { pos_ += n; }
    void set_mark(std::size_t position) { mark_ = position; }

private:
    const char* data_;
    std::size_t size_;
    std::size_t pos_;
    std::size_t mark_;
};

/// Reads an ASCII body: one record per line, values separated by spaces or tabs; blank
/// lines between records are ignored; LF or CRLF.
class AsciiSource {
public:
    static constexpr bool kBinary = false;

    AsciiSource(std::span<const char> bytes, std::size_t position, std::size_t line)
        : data_(bytes.data()), size_(bytes.size()), pos_(position), line_(line) {}

    bool begin_record();
    ReadStatus read(PlyScalar type, double& value);
    ReadStatus end_record();
    bool at_end();
    std::string location() const { return "line " + std::to_string(line_); }
    std::size_t remaining() const { return size_ - pos_; }
    /// A value takes at least one digit and one separator.
    static std::size_t min_value_bytes(PlyScalar) { return 2; }
    std::string_view last_token() const { return token_; }

private:
    static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
    void skip_blanks(std::size_t end) {
        while (pos_ < end && is_blank(data_[pos_])) ++pos_;
    }

    const char* data_;
    std::size_t size_;
    std::size_t pos_;
    std::size_t line_;
    std::size_t line_end_ = 0;
    std::string_view token_;
};

}  // namespace anascan::io::ply_detail
