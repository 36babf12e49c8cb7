#pragma once
/// \file
/// What the XML section says about each scan: its name, pose, where its points are and how
/// each point field is encoded (ASTM E2807 sections 9 and 10, the data3D element).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "xml_tree.hpp"

namespace anascan::io::e57 {

/// How a field is stored in its bytestream (bitPackCodec).
enum class FieldKind { kInteger, kScaledInteger, kFloat };

/// One terminal field of a compressed vector's prototype, in bytestream order.
struct FieldSpec {
    std::string name;  ///< Path inside the prototype, e.g. "cartesianX".
    FieldKind kind = FieldKind::kInteger;
    std::int64_t minimum = 0;  ///< Integer and ScaledInteger: raw range.
    std::int64_t maximum = 0;
    double scale = 1.0;  ///< ScaledInteger: value = raw * scale + offset.
    double offset = 0.0;
    bool single_precision = false;  ///< Float: 32-bit when true, else 64-bit.
    int bits = 0;                   ///< Bits per value in the bytestream (0 for constants).
};

/// A compressed vector: where its binary section starts, how many records, which fields.
struct CompressedVectorSpec {
    std::uint64_t physical_offset = 0;
    std::uint64_t record_count = 0;
    std::vector<FieldSpec> fields;
    std::uint64_t xml_byte = 0;
};

/// One data3D entry.
struct ScanSpec {
    std::string name;
    std::string guid;
    std::optional<Pose> T_file_scan;  ///< The pose element; absent when the scan has none.
    CompressedVectorSpec points;
    bool has_color_limits = false;  ///< colorLimits given (else the colour fields' range).
    double color_minimum = 0.0;
    double color_maximum = 255.0;
};

/// Everything the reader needs from the XML section.
struct FileSpec {
    std::string guid;
    std::vector<ScanSpec> scans;
    std::size_t image_count = 0;  ///< images2D entries (not read).
};

/// Reads the e57Root element. Errors name the file and the element's byte offset.
Expected<FileSpec> read_file_spec(const XmlNode& root, const XmlSource& where);

/// Bits that bitPackCodec uses for an integer in [minimum, maximum] (0 when equal).
int bits_for_range(std::int64_t minimum, std::int64_t maximum);

}  // namespace anascan::io::e57
