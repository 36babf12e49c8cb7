#pragma once
/// \file
/// The page layer of an E57 file (ASTM E2807 section 8): 1024-byte physical pages, each
/// 1020 bytes of data followed by the big-endian CRC-32C of those bytes. Everything above
/// this layer (XML, binary sections) is addressed by physical offsets but read as the
/// "logical" byte stream with the checksums removed.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::io::e57 {

inline constexpr std::uint64_t kPageBytes = 1024;
inline constexpr std::uint64_t kPageDataBytes = kPageBytes - 4;
inline constexpr std::uint64_t kHeaderBytes = 48;

/// The 48-byte file header at physical offset 0.
struct FileHeader {
    std::uint32_t version_major = 1;
    std::uint32_t version_minor = 0;
    std::uint64_t physical_length = 0;
    std::uint64_t xml_physical_offset = 0;
    std::uint64_t xml_logical_length = 0;
    std::uint64_t page_size = kPageBytes;
};

/// Physical offset of logical byte `logical` (its page, then its place in the page).
constexpr std::uint64_t to_physical(std::uint64_t logical) {
    return logical / kPageDataBytes * kPageBytes + logical % kPageDataBytes;
}

/// Logical offset of physical byte `physical`; a checksum byte maps past its page's data.
constexpr std::uint64_t to_logical(std::uint64_t physical) {
    return physical / kPageBytes * kPageDataBytes + physical % kPageBytes;
}

/// A whole E57 file whose every page CRC has been checked. Immutable; thread-safe to read.
class PagedFile {
public:
    /// Checks the signature, the header's lengths against the bytes, and every page's
    /// CRC-32C. Errors name the source and the byte offset.
    static Expected<PagedFile> open(std::span<const char> bytes, std::string_view source);

    const FileHeader& header() const { return header_; }
    const std::string& source() const { return source_; }

    /// `length` logical bytes from physical offset `physical`; `what` names them in errors.
    Expected<std::span<const std::uint8_t>> read(std::uint64_t physical, std::uint64_t length,
                                                 std::string_view what) const;

    /// "SOURCE: byte N: what" as an error of `code`.
    Error error_at(ErrorCode code, std::uint64_t physical, std::string_view what) const;

private:
    PagedFile() = default;
    std::string source_;
    FileHeader header_;
    std::vector<std::uint8_t> logical_;
};

/// Little-endian field readers over a span (the caller has checked the length).
std::uint16_t load_u16(std::span<const std::uint8_t> bytes, std::size_t at);
std::uint64_t load_u64(std::span<const std::uint8_t> bytes, std::size_t at);

/// Splits a logical byte stream into checksummed pages (the last page zero-padded).
std::vector<char> paginate(std::span<const std::uint8_t> logical);

}  // namespace anascan::io::e57
