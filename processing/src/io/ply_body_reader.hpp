#pragma once
// Private to processing/src/io: reads the elements of a PLY body through a Source
// (BinarySource<kSwap> or AsciiSource) into PlyData. Every count is checked against the
// bytes left before anything is allocated, and every error names the source, the location
// ("byte N" / "line N"), the element record and what was wrong.

#include <algorithm>
#include <string>
#include <utility>

#include "ply_header.hpp"
#include "ply_source.hpp"
#include "ply_vertex.hpp"

namespace anascan::io::ply_detail {

/// "vertices", "faces", "range_grids": for "the header announces 40256 vertices".
std::string plural(const std::string& element_name);

/// Reads one body; one instance per parse.
template <class Source>
class BodyReader {
public:
    BodyReader(Source& source, const PlyHeader& header, std::string_view name, PlyData& data)
        : src_(source), header_(header), name_(name), data_(data) {
        for (const PlyElement& element : header.elements) {
            if (element.name == "vertex") vertex_count_ = element.count;
        }
    }

    /// Reads every element, then checks that nothing follows the last one.
    Expected<void> read_all() {
        for (const PlyElement& element : header_.elements) {
            if (Expected<void> done = read_element(element); !done) return done;
        }
        element_ = nullptr;
        if (!src_.at_end()) {
            return error(ErrorCode::kFormat, std::to_string(src_.remaining()) +
                                                 " bytes of unexpected data after the last "
                                                 "element (trailing garbage, or a header count "
                                                 "too small)");
        }
        return {};
    }

private:
    Expected<void> read_element(const PlyElement& element) {
        element_ = &element;
        index_ = 0;
        if (element.name == "vertex") return read_vertices(element);
        if (element.name == "face") return read_faces(element);
        if (element.name == "range_grid") return read_range_grid(element);
        data_.skipped_elements.push_back(element.name);
        return skip_element(element);
    }

    Unexpected<Error> error(ErrorCode code, const std::string& what) const {
        std::string message = std::string(name_) + ": " + src_.location() + ": ";
        if (element_ != nullptr) {
            message += element_->name + " " + std::to_string(index_) + " of " +
                       std::to_string(element_->count) + ": ";
        }
        return fail(code, message + what);
    }

    // An error about the element as a whole (not one of its records).
    Unexpected<Error> element_error(ErrorCode code, const std::string& what) const {
        return fail(code, std::string(name_) + ": " + src_.location() + ": element " +
                              element_->name + ": " + what);
    }

    Unexpected<Error> ends_early() const {
        return error(ErrorCode::kTruncated, "file ends early (truncated; the header announces " +
                                                std::to_string(element_->count) + " " +
                                                plural(element_->name) + ")");
    }

    Unexpected<Error> value_error(ReadStatus status, const PlyProperty& property,
                                  PlyScalar type) const {
        std::string token(src_.last_token().substr(0, 40));
        for (char& c : token) {
            if (c < ' ' || c > '~') c = '?';  // keep messages printable
        }
        const std::string what = "property '" + property.name + "': ";
        switch (status) {
            case ReadStatus::kEnd:
                if constexpr (Source::kBinary) return ends_early();
                return error(ErrorCode::kFormat, what + "the line ends before this value (" +
                                                     "fewer values than properties)");
            case ReadStatus::kNotANumber:
                return error(ErrorCode::kFormat,
                             what + "'" + token + "' is not " +
                                 (is_integer(type) ? "an integer" : "a number"));
            case ReadStatus::kOutOfRange:
                return error(ErrorCode::kFormat, what + "'" + token + "' is out of range for " +
                                                     std::string(scalar_name(type)));
            case ReadStatus::kExtra:
            case ReadStatus::kOk:
                break;
        }
        return error(ErrorCode::kFormat, "unexpected value '" + token + "' after the last " +
                                             "property (more values than properties)");
    }

    Expected<double> value(const PlyProperty& property, PlyScalar type) {
        double number = 0.0;
        const ReadStatus status = src_.read(type, number);
        if (status == ReadStatus::kOk) return number;
        return value_error(status, property, type);
    }

    Expected<std::size_t> list_count(const PlyProperty& property) {
        const Expected<double> count = value(property, property.count_type);
        if (!count) return fail(count.error());
        if (*count < 0) {
            return error(ErrorCode::kFormat, "list '" + property.name + "' has a negative count");
        }
        const double room =
            static_cast<double>(src_.remaining() / src_.min_value_bytes(property.type));
        if (*count > room) {
            return error(ErrorCode::kTruncated,
                         "list '" + property.name + "' announces " +
                             std::to_string(static_cast<std::uint64_t>(*count)) +
                             " entries, more than the data left (" +
                             std::to_string(src_.remaining()) + " bytes; truncated or corrupt)");
        }
        return static_cast<std::size_t>(*count);
    }

    Expected<void> skip_items(const PlyProperty& property, std::size_t count) {
        if constexpr (Source::kBinary) {
            src_.skip(count * scalar_size(property.type));  // list_count bounded count
        } else {
            for (std::size_t i = 0; i < count; ++i) {
                if (Expected<double> item = value(property, property.type); !item) {
                    return fail(item.error());
                }
            }
        }
        return {};
    }

    // Visits every record: on_scalar(k, value) for scalar property k, on_list(k, count)
    // for list property k (which must consume the list's items).
    template <class OnScalar, class OnList>
    Expected<void> walk(const PlyElement& element, OnScalar&& on_scalar, OnList&& on_list) {
        for (index_ = 0; index_ < element.count; ++index_) {
            if (!src_.begin_record()) return ends_early();
            for (std::size_t k = 0; k < element.properties.size(); ++k) {
                const PlyProperty& property = element.properties[k];
                if (property.is_list) {
                    const Expected<std::size_t> count = list_count(property);
                    if (!count) return fail(count.error());
                    if (Expected<void> done = on_list(k, *count); !done) return done;
                } else {
                    const Expected<double> number = value(property, property.type);
                    if (!number) return fail(number.error());
                    on_scalar(k, *number);
                }
            }
            const ReadStatus status = src_.end_record();
            if (status != ReadStatus::kOk)
                return value_error(status, element.properties.back(),
                                   element.properties.back().type);
        }
        return {};
    }

    Expected<void> skip_element(const PlyElement& element) {
        if constexpr (Source::kBinary) {
            if (!element.has_lists()) {
                if (!fits(element)) return truncated_fixed(element);
                src_.skip(element.count * element.fixed_record_bytes());
                return {};
            }
        }
        return walk(
            element, [](std::size_t, double) {},
            [&](std::size_t k, std::size_t count) {
                return skip_items(element.properties[k], count);
            });
    }

    // True when the data left can hold `element`'s records at their smallest size.
    bool fits(const PlyElement& element) const {
        if (element.count == 0) return true;
        std::size_t smallest = 0;
        for (const PlyProperty& property : element.properties) {
            smallest +=
                src_.min_value_bytes(property.is_list ? property.count_type : property.type);
        }
        const std::size_t slack = Source::kBinary ? 0 : 1;  // ASCII: no final newline
        return element.count <= (src_.remaining() + slack) / smallest;
    }

    // A fixed-size binary element that does not fit: name the first incomplete record.
    Unexpected<Error> truncated_fixed(const PlyElement& element) {
        if constexpr (Source::kBinary) {
            const std::size_t record = element.fixed_record_bytes();
            const std::size_t whole = src_.remaining() / record;
            index_ = whole;
            src_.set_mark(src_.position() + whole * record);
        }
        return ends_early();
    }

    // An element that cannot fit: find the exact error by reading without storing.
    Unexpected<Error> doomed(const PlyElement& element) {
        if (Source::kBinary && !element.has_lists()) return truncated_fixed(element);
        if (Expected<void> skipped = skip_element(element); !skipped) return fail(skipped.error());
        return ends_early();  // unreachable: a count that does not fit fails above
    }

    Expected<void> read_vertices(const PlyElement& element);
    Expected<void> read_faces(const PlyElement& element);
    Expected<void> read_polygon(const PlyProperty& property, std::size_t count);
    Expected<void> read_range_grid(const PlyElement& element);
    Expected<void> read_grid_entry(const PlyProperty& property, std::size_t count, RangeGrid& grid);

    Source& src_;
    const PlyHeader& header_;
    std::string_view name_;
    PlyData& data_;
    std::uint64_t vertex_count_ = 0;
    const PlyElement* element_ = nullptr;
    std::uint64_t index_ = 0;
    std::vector<std::int32_t> polygon_;
};

}  // namespace anascan::io::ply_detail

#include "ply_body_elements.hpp"
