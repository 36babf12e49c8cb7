#include "ply_header.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <utility>

namespace anascan::io::ply_detail {
namespace {

struct ScalarName {
    std::string_view name;
    PlyScalar type;
};

constexpr std::array<ScalarName, 16> kScalarNames{{
    {"char", PlyScalar::kInt8},
    {"int8", PlyScalar::kInt8},
    {"uchar", PlyScalar::kUint8},
    {"uint8", PlyScalar::kUint8},
    {"short", PlyScalar::kInt16},
    {"int16", PlyScalar::kInt16},
    {"ushort", PlyScalar::kUint16},
    {"uint16", PlyScalar::kUint16},
    {"int", PlyScalar::kInt32},
    {"int32", PlyScalar::kInt32},
    {"uint", PlyScalar::kUint32},
    {"uint32", PlyScalar::kUint32},
    {"float", PlyScalar::kFloat32},
    {"float32", PlyScalar::kFloat32},
    {"double", PlyScalar::kFloat64},
    {"float64", PlyScalar::kFloat64},
}};

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view trim(std::string_view text) {
    while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
    return text;
}

std::vector<std::string_view> split_words(std::string_view text) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && is_blank(text[i])) ++i;
        const std::size_t start = i;
        while (i < text.size() && !is_blank(text[i])) ++i;
        if (i > start) words.push_back(text.substr(start, i - start));
    }
    return words;
}

template <class T>
bool parse_whole(std::string_view word, T& value) {
    const char* end = word.data() + word.size();
    const auto [ptr, ec] = std::from_chars(word.data(), end, value);
    return ec == std::errc() && ptr == end;
}

// Splits the header into lines (LF or CRLF) and counts them.
class LineReader {
public:
    explicit LineReader(std::span<const char> bytes) : bytes_(bytes) {}

    bool next(std::string_view& line) {
        if (pos_ >= bytes_.size()) return false;
        const std::string_view rest(bytes_.data() + pos_, bytes_.size() - pos_);
        const std::size_t newline = rest.find('\n');
        line = trim(rest.substr(0, newline));
        pos_ = newline == std::string_view::npos ? bytes_.size() : pos_ + newline + 1;
        ++number_;
        return true;
    }
    std::size_t number() const { return number_; }
    std::size_t position() const { return pos_; }

private:
    std::span<const char> bytes_;
    std::size_t pos_ = 0;
    std::size_t number_ = 0;
};

// Interprets header lines one at a time.
class HeaderParser {
public:
    explicit HeaderParser(std::string_view source) : source_(source) {}

    Expected<void> handle(std::string_view line, std::size_t number);
    Expected<void> finish(std::size_t number);
    PlyHeader& header() { return header_; }

private:
    Unexpected<Error> error(ErrorCode code, const std::string& what) const {
        return fail(code, std::string(source_) + ": line " + std::to_string(number_) + ": " + what);
    }
    Expected<void> on_format(const std::vector<std::string_view>& words);
    Expected<void> on_comment(std::string_view text);
    Expected<void> on_obj_info(std::string_view line, const std::vector<std::string_view>& words);
    Expected<void> on_element(const std::vector<std::string_view>& words);
    Expected<void> on_property(const std::vector<std::string_view>& words);
    Expected<PlyScalar> type_named(std::string_view name) const;

    std::string_view source_;
    PlyHeader header_;
    std::size_t number_ = 0;
    bool format_seen_ = false;
};

Expected<void> HeaderParser::handle(std::string_view line, std::size_t number) {
    number_ = number;
    const std::vector<std::string_view> words = split_words(line);
    if (words.empty()) return {};
    const std::string_view keyword = words[0];
    if (keyword == "format") return on_format(words);
    if (keyword == "comment") return on_comment(trim(line.substr(keyword.size())));
    if (keyword == "obj_info") return on_obj_info(line, words);
    if (keyword == "element") return on_element(words);
    if (keyword == "property") return on_property(words);
    return error(ErrorCode::kFormat, "unknown header keyword '" + std::string(keyword) + "'");
}

Expected<void> HeaderParser::on_format(const std::vector<std::string_view>& words) {
    if (format_seen_) return error(ErrorCode::kFormat, "second 'format' line");
    if (words.size() != 3) return error(ErrorCode::kFormat, "expected 'format <type> 1.0'");
    const std::string_view type = words[1];
    if (type == "ascii") {
        header_.format = PlyFormat::kAscii;
    } else if (type == "binary_little_endian") {
        header_.format = PlyFormat::kBinaryLittleEndian;
    } else if (type == "binary_big_endian") {
        header_.format = PlyFormat::kBinaryBigEndian;
    } else {
        return error(ErrorCode::kUnsupported, "unknown format '" + std::string(type) +
                                                  "' (expected ascii, binary_little_endian or "
                                                  "binary_big_endian)");
    }
    if (words[2] != "1.0" && words[2] != "1") {
        return error(ErrorCode::kUnsupported,
                     "PLY version '" + std::string(words[2]) + "' (only 1.0 is defined)");
    }
    format_seen_ = true;
    return {};
}

Expected<void> HeaderParser::on_comment(std::string_view text) {
    if (!text.starts_with(kOriginComment)) {
        header_.comments.emplace_back(text);
        return {};
    }
    const std::vector<std::string_view> words = split_words(text.substr(kOriginComment.size()));
    Eigen::Vector3d origin;
    bool ok = words.size() == 3;
    for (int i = 0; ok && i < 3; ++i)
        ok = parse_whole(words[i], origin[i]) && std::isfinite(origin[i]);
    if (!ok) {
        return error(ErrorCode::kFormat, "expected 'comment " + std::string(kOriginComment) +
                                             " X Y Z' with three finite numbers");
    }
    header_.origin_m = origin;
    return {};
}

Expected<void> HeaderParser::on_obj_info(std::string_view line,
                                         const std::vector<std::string_view>& words) {
    header_.comments.emplace_back(line);
    const bool is_cols = words.size() >= 2 && words[1] == "num_cols";
    const bool is_rows = words.size() >= 2 && words[1] == "num_rows";
    if (!is_cols && !is_rows) return {};
    std::int64_t value = 0;
    if (words.size() != 3 || !parse_whole(words[2], value) || value < 0 ||
        value > static_cast<std::int64_t>(kMaxElementCount)) {
        return error(ErrorCode::kFormat,
                     "expected 'obj_info " + std::string(words[1]) + " N' with a count N >= 0");
    }
    (is_cols ? header_.num_cols : header_.num_rows) = value;
    return {};
}

Expected<void> HeaderParser::on_element(const std::vector<std::string_view>& words) {
    if (words.size() != 3) return error(ErrorCode::kFormat, "expected 'element <name> <count>'");
    PlyElement element;
    element.name = words[1];
    for (const PlyElement& other : header_.elements) {
        if (other.name == element.name) {
            return error(ErrorCode::kFormat, "second element named '" + element.name + "'");
        }
    }
    if (!parse_whole(words[2], element.count)) {
        return error(ErrorCode::kFormat, "element " + element.name + ": count '" +
                                             std::string(words[2]) + "' is not a number >= 0");
    }
    if (element.count > kMaxElementCount) {
        return error(ErrorCode::kFormat, "element " + element.name + ": count " +
                                             std::string(words[2]) + " is absurd (more than " +
                                             std::to_string(kMaxElementCount) + ")");
    }
    header_.elements.push_back(std::move(element));
    return {};
}

Expected<PlyScalar> HeaderParser::type_named(std::string_view name) const {
    if (const std::optional<PlyScalar> type = scalar_from_name(name)) return *type;
    return error(ErrorCode::kUnsupported, "unknown property type '" + std::string(name) +
                                              "' (expected char, uchar, short, ushort, int, "
                                              "uint, float, double or int8 ... float64)");
}

Expected<void> HeaderParser::on_property(const std::vector<std::string_view>& words) {
    if (header_.elements.empty()) return error(ErrorCode::kFormat, "property before any element");
    PlyElement& element = header_.elements.back();
    PlyProperty property;
    const bool is_list = words.size() >= 2 && words[1] == "list";
    if (words.size() != (is_list ? 5u : 3u)) {
        return error(ErrorCode::kFormat, is_list ? "expected 'property list <count type> "
                                                   "<item type> <name>'"
                                                 : "expected 'property <type> <name>'");
    }
    property.is_list = is_list;
    property.name = words.back();
    const Expected<PlyScalar> type = type_named(words[is_list ? 3 : 1]);
    if (!type) return fail(type.error());
    property.type = *type;
    if (is_list) {
        const Expected<PlyScalar> count_type = type_named(words[2]);
        if (!count_type) return fail(count_type.error());
        if (!is_integer(*count_type)) {
            return error(ErrorCode::kFormat,
                         "list count type '" + std::string(words[2]) + "' is not an integer type");
        }
        property.count_type = *count_type;
    }
    for (const PlyProperty& other : element.properties) {
        if (other.name == property.name) {
            return error(ErrorCode::kFormat, "element " + element.name +
                                                 ": second property named '" + property.name + "'");
        }
    }
    element.properties.push_back(std::move(property));
    return {};
}

Expected<void> HeaderParser::finish(std::size_t number) {
    number_ = number;
    if (!format_seen_) return error(ErrorCode::kFormat, "no 'format' line before end_header");
    for (const PlyElement& element : header_.elements) {
        if (element.properties.empty() && element.count > 0) {
            return error(ErrorCode::kFormat, "element " + element.name + " has no properties");
        }
    }
    return {};
}

}  // namespace

std::size_t scalar_size(PlyScalar type) {
    constexpr std::array<std::size_t, 8> kSizes{1, 1, 2, 2, 4, 4, 4, 8};
    return kSizes[static_cast<std::size_t>(type)];
}

std::string_view scalar_name(PlyScalar type) {
    return kScalarNames[2 * static_cast<std::size_t>(type)].name;
}

bool is_integer(PlyScalar type) {
    return type != PlyScalar::kFloat32 && type != PlyScalar::kFloat64;
}

std::optional<PlyScalar> scalar_from_name(std::string_view name) {
    for (const ScalarName& entry : kScalarNames) {
        if (entry.name == name) return entry.type;
    }
    return std::nullopt;
}

bool PlyElement::has_lists() const {
    for (const PlyProperty& property : properties) {
        if (property.is_list) return true;
    }
    return false;
}

std::size_t PlyElement::fixed_record_bytes() const {
    std::size_t bytes = 0;
    for (const PlyProperty& property : properties) {
        bytes += scalar_size(property.is_list ? property.count_type : property.type);
    }
    return bytes;
}

Expected<PlyHeader> parse_ply_header(std::span<const char> bytes, std::string_view source_name) {
    if (bytes.empty())
        return fail(ErrorCode::kEmpty, std::string(source_name) + ": empty file (0 bytes)");
    LineReader lines(bytes);
    std::string_view line;
    if (!lines.next(line) || line != "ply") {
        return fail(ErrorCode::kFormat, std::string(source_name) +
                                            ": line 1: not a PLY file (the first line must be "
                                            "'ply')");
    }
    HeaderParser parser(source_name);
    while (lines.next(line)) {
        if (line == "end_header") {
            if (Expected<void> done = parser.finish(lines.number()); !done)
                return fail(done.error());
            PlyHeader& header = parser.header();
            header.body_offset = lines.position();
            header.body_line = lines.number() + 1;
            return std::move(header);
        }
        if (Expected<void> handled = parser.handle(line, lines.number()); !handled) {
            return fail(handled.error());
        }
    }
    return fail(ErrorCode::kTruncated, std::string(source_name) + ": line " +
                                           std::to_string(lines.number()) +
                                           ": the header has no 'end_header' line (file "
                                           "truncated, or not a PLY file)");
}

}  // namespace anascan::io::ply_detail
