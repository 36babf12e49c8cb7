#pragma once
/// \file
/// The binary section of a compressed vector (ASTM E2807 section 9.6): a section header,
/// then data packets whose bytestream buffers, one per prototype field, join into one
/// bit-packed stream per field; and the reader of those bit-packed values (bitPackCodec).

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "paged_file.hpp"
#include "schema.hpp"

namespace anascan::io::e57 {

inline constexpr std::uint64_t kSectionHeaderBytes = 32;
inline constexpr std::uint64_t kDataPacketHeaderBytes = 6;
inline constexpr std::uint64_t kMaxPacketBytes = 65536;

/// Collects each field's bytestream over the data packets of the compressed vector `cv`.
/// Checks the section id, that the section and every packet fit, that the record count
/// fits in the section's bytes (so a lying count cannot make memory grow), and that each
/// stream holds all records. Errors name the file, the byte offset and `what` (the scan).
Expected<std::vector<std::vector<std::uint8_t>>> read_bytestreams(const PagedFile& file,
                                                                  const CompressedVectorSpec& cv,
                                                                  std::string_view what);

/// Reads consecutive values of a given width from a little-endian, least-significant-bit
/// first stream. The caller guarantees the stream holds the bits it asks for.
class BitReader {
public:
    explicit BitReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
    std::uint64_t next(int bits);

private:
    std::span<const std::uint8_t> bytes_;
    std::uint64_t bit_ = 0;
};

/// The next value of field `f` from its reader: raw integers for Integer fields, scaled
/// values for ScaledInteger, the stored float for Float.
double next_value(const FieldSpec& f, BitReader& reader);

/// The next raw integer of an Integer or ScaledInteger field (minimum + stored bits).
std::int64_t next_integer(const FieldSpec& f, BitReader& reader);

}  // namespace anascan::io::e57
