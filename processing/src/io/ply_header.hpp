#pragma once
// Private to processing/src/io: the parsed PLY header and the PLY scalar types, shared by
// the reader and the writer.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/io/ply.hpp"

namespace anascan::io::ply_detail {

/// The eight PLY scalar types (each has two names: `uchar` / `uint8`, ...).
enum class PlyScalar : std::uint8_t {
    kInt8,
    kUint8,
    kInt16,
    kUint16,
    kInt32,
    kUint32,
    kFloat32,
    kFloat64
};

/// Bytes of one value in a binary body.
std::size_t scalar_size(PlyScalar type);

/// The type's canonical PLY name ("uchar", "float", ...).
std::string_view scalar_name(PlyScalar type);

/// True for the six integer types.
bool is_integer(PlyScalar type);

/// The type named `name` (either spelling), or nothing for an unknown name.
std::optional<PlyScalar> scalar_from_name(std::string_view name);

/// Largest element count we accept: indices are int32.
inline constexpr std::uint64_t kMaxElementCount = 0x7fffffff;

/// One `property` line.
struct PlyProperty {
    std::string name;
    PlyScalar type = PlyScalar::kFloat32;  ///< The value (for a list: each item's) type.
    bool is_list = false;
    PlyScalar count_type = PlyScalar::kUint8;  ///< Type of a list's count.
};

/// One `element` line and its properties.
struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;

    /// True when some property is a list (records have variable size).
    bool has_lists() const;
    /// Binary bytes of a record not counting list items (exact when there are no lists).
    std::size_t fixed_record_bytes() const;
};

/// Everything between `ply` and `end_header`.
struct PlyHeader {
    PlyFormat format = PlyFormat::kAscii;
    std::vector<PlyElement> elements;
    std::vector<std::string> comments;        ///< `comment` text and `obj_info ...` lines.
    std::optional<Eigen::Vector3d> origin_m;  ///< From `comment anascan origin_m X Y Z`.
    std::optional<std::int64_t> num_cols;     ///< From `obj_info num_cols N`.
    std::optional<std::int64_t> num_rows;     ///< From `obj_info num_rows M`.
    std::size_t body_offset = 0;              ///< First byte after the `end_header` line.
    std::size_t body_line = 1;                ///< Line number (1-based) of the first body line.
};

/// The comment prefix that carries the cloud's double-precision origin.
inline constexpr std::string_view kOriginComment = "anascan origin_m";

/// Parses the header; errors start with "<source_name>: line N: ".
Expected<PlyHeader> parse_ply_header(std::span<const char> bytes, std::string_view source_name);

}  // namespace anascan::io::ply_detail
