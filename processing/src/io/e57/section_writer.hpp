#pragma once
/// \file
/// The writing half of bitPackCodec: a scan's points as prototype fields, their bit-packed
/// bytestreams, and the compressed-vector section that carries them in data packets.

#include <cstdint>
#include <string>
#include <vector>

#include "anascan/processing/io/e57.hpp"
#include "schema.hpp"

namespace anascan::io::e57 {

/// A prototype field and its bytestream.
struct FieldStream {
    FieldSpec spec;
    std::vector<std::uint8_t> bytes;
};

/// The fields our writer emits for `scan`: cartesianX/Y/Z (64-bit Float), intensity
/// (32-bit Float), colorRed/Green/Blue (Integer 0..255), rowIndex/columnIndex (Integer)
/// when the grid is set. kInvalidArgument when the cloud or its grid is inconsistent.
Expected<std::vector<FieldStream>> encode_fields(const E57Scan& scan);

/// Appends `value` (the stored, minimum-relative bits) to the field's bytestream. Streams
/// are appended to value by value; use one BitPacker per stream.
class BitPacker {
public:
    explicit BitPacker(FieldStream& field) : field_(field) {}
    void put(std::uint64_t value);

private:
    FieldStream& field_;
    std::uint64_t bit_ = 0;
};

/// The prototype element declaring `fields` (Integer, ScaledInteger, Float).
std::string prototype_xml(const std::vector<FieldStream>& fields);

/// Appends a compressed-vector section for `record_count` records to `logical` (which
/// must end on a 4-byte boundary) and returns the section's physical offset.
std::uint64_t append_section(std::vector<std::uint8_t>& logical,
                             const std::vector<FieldStream>& fields, std::uint64_t record_count);

}  // namespace anascan::io::e57
