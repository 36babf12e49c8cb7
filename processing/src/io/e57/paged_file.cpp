#include "paged_file.hpp"

#include <algorithm>
#include <cstring>
#include <string_view>

#include "crc32c.hpp"

namespace anascan::io::e57 {
namespace {

constexpr std::string_view kSignature = "ASTM-E57";

std::uint32_t load_u32(std::span<const std::uint8_t> bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | bytes[at + i];
    return v;
}

std::uint32_t load_be32(std::span<const std::uint8_t> bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | bytes[at + i];
    return v;
}

std::string hex32(std::uint32_t v) {
    char text[11];
    std::snprintf(text, sizeof text, "0x%08X", v);
    return text;
}

FileHeader parse_header(std::span<const std::uint8_t> b) {
    return FileHeader{.version_major = load_u32(b, 8),
                      .version_minor = load_u32(b, 12),
                      .physical_length = load_u64(b, 16),
                      .xml_physical_offset = load_u64(b, 24),
                      .xml_logical_length = load_u64(b, 32),
                      .page_size = load_u64(b, 40)};
}

}  // namespace

std::uint16_t load_u16(std::span<const std::uint8_t> bytes, std::size_t at) {
    return static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8));
}

std::uint64_t load_u64(std::span<const std::uint8_t> bytes, std::size_t at) {
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | bytes[at + i];
    return v;
}

Error PagedFile::error_at(ErrorCode code, std::uint64_t physical, std::string_view what) const {
    return Error{code, source_ + ": byte " + std::to_string(physical) + ": " + std::string(what)};
}

Expected<PagedFile> PagedFile::open(std::span<const char> bytes, std::string_view source) {
    PagedFile file;
    file.source_ = std::string(source);
    const std::span<const std::uint8_t> b(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                          bytes.size());
    if (b.size() < kHeaderBytes || std::memcmp(b.data(), kSignature.data(), 8) != 0) {
        return fail(
            file.error_at(ErrorCode::kFormat, 0, "not an E57 file (no 'ASTM-E57' signature)"));
    }
    file.header_ = parse_header(b);
    const FileHeader& h = file.header_;
    if (h.version_major != 1) {
        return fail(file.error_at(
            ErrorCode::kUnsupported, 8,
            "E57 version " + std::to_string(h.version_major) + " (this reader reads version 1)"));
    }
    if (h.page_size != kPageBytes) {
        return fail(file.error_at(
            ErrorCode::kUnsupported, 40,
            "page size " + std::to_string(h.page_size) + " (E57 pages are 1024 bytes)"));
    }
    if (h.physical_length != b.size() || b.size() % kPageBytes != 0) {
        return fail(file.error_at(ErrorCode::kTruncated, 16,
                                  "the header announces " + std::to_string(h.physical_length) +
                                      " bytes in whole 1024-byte pages, the file has " +
                                      std::to_string(b.size())));
    }
    file.logical_.reserve(b.size() / kPageBytes * kPageDataBytes);
    for (std::size_t page = 0; page < b.size() / kPageBytes; ++page) {
        const std::span<const std::uint8_t> data = b.subspan(page * kPageBytes, kPageDataBytes);
        const std::uint32_t stored = load_be32(b, page * kPageBytes + kPageDataBytes);
        const std::uint32_t computed = crc32c(data);
        if (stored != computed) {
            return fail(file.error_at(ErrorCode::kFormat, page * kPageBytes,
                                      "page " + std::to_string(page) +
                                          " fails its CRC-32C (stored " + hex32(stored) +
                                          ", computed " + hex32(computed) + ")"));
        }
        file.logical_.insert(file.logical_.end(), data.begin(), data.end());
    }
    return file;
}

Expected<std::span<const std::uint8_t>> PagedFile::read(std::uint64_t physical,
                                                        std::uint64_t length,
                                                        std::string_view what) const {
    const std::uint64_t logical = to_logical(physical);
    const bool in_data = physical % kPageBytes < kPageDataBytes;
    if (!in_data || logical > logical_.size() || length > logical_.size() - logical) {
        return fail(error_at(ErrorCode::kTruncated, physical,
                             std::string(what) + " of " + std::to_string(length) +
                                 " bytes does not fit in the file (" +
                                 std::to_string(header_.physical_length) + " bytes)"));
    }
    return std::span<const std::uint8_t>(logical_).subspan(logical, length);
}

std::vector<char> paginate(std::span<const std::uint8_t> logical) {
    const std::size_t pages =
        std::max<std::size_t>(1, (logical.size() + kPageDataBytes - 1) / kPageDataBytes);
    std::vector<char> out(pages * kPageBytes, 0);
    for (std::size_t page = 0; page < pages; ++page) {
        std::uint8_t* dst = reinterpret_cast<std::uint8_t*>(out.data()) + page * kPageBytes;
        const std::size_t from = page * kPageDataBytes;
        const std::size_t n = std::min<std::size_t>(kPageDataBytes, logical.size() - from);
        if (n > 0) std::memcpy(dst, logical.data() + from, n);
        const std::uint32_t crc = crc32c({dst, kPageDataBytes});
        for (int i = 0; i < 4; ++i) dst[kPageDataBytes + i] = std::uint8_t(crc >> (24 - 8 * i));
    }
    return out;
}

}  // namespace anascan::io::e57
