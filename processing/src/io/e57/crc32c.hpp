#pragma once
/// \file
/// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78), the checksum of E57 pages.
/// Debian 12 packages no CRC-32C library for C++ (zlib's crc32 is the other polynomial),
/// so it is a 256-entry table here.

#include <cstdint>
#include <span>

namespace anascan::io::e57 {

/// CRC-32C of `bytes` (initial value and final xor 0xFFFFFFFF): "123456789" -> 0xE3069283.
std::uint32_t crc32c(std::span<const std::uint8_t> bytes);

}  // namespace anascan::io::e57
