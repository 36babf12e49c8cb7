// Hostile E57 files: every error names the file and a byte offset, and a lying length or
// count is caught before memory is allocated for it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "e57_test_files.hpp"

namespace anascan::io {
namespace {

using namespace e57_test;
using ::testing::HasSubstr;
using ::testing::StartsWith;

/// Logical offsets in a file of one scan written by assemble_file.
constexpr std::size_t kSection = 48;                 // the compressed-vector section
constexpr std::size_t kFirstPacket = kSection + 32;  // its first data packet
constexpr std::size_t kFirstBufferLength = kFirstPacket + 6;

e57::ScanSection small_section(std::uint64_t records) {
    std::vector<std::uint64_t> values(records);
    for (std::uint64_t i = 0; i < records; ++i) values[i] = std::bit_cast<std::uint64_t>(double(i));
    e57::ScanSection s{.name = "small", .record_count = records};
    for (const char* axis : {"cartesianX", "cartesianY", "cartesianZ"})
        s.fields.push_back(field(float_spec(axis, false), values));
    return s;
}

std::vector<char> small_file(std::uint64_t records = 200) {
    const e57::ScanSection s = small_section(records);
    return e57::assemble_file(std::span(&s, 1));
}

Error expect_error(std::span<const char> bytes, ErrorCode code) {
    const auto read = parse_e57(bytes, "hostile.e57");
    EXPECT_FALSE(read) << "read " << (read ? read->scans.size() : 0) << " scans";
    if (read) return {};
    EXPECT_EQ(read.error().code, code) << read.error().message;
    EXPECT_THAT(read.error().message, StartsWith("hostile.e57: byte "));
    return read.error();
}

std::vector<char> edited(std::vector<std::uint8_t> logical) { return e57::paginate(logical); }

TEST(E57Errors, NotAnE57File) {
    const std::string text = "ply\nformat ascii 1.0\nend_header\n";
    const Error e = expect_error(std::span(text.data(), text.size()), ErrorCode::kFormat);
    EXPECT_THAT(e.message, HasSubstr("byte 0: not an E57 file"));
}

TEST(E57Errors, BadPageChecksumNamesThePage) {
    std::vector<char> bytes = small_file();
    bytes[1500] = char(bytes[1500] ^ 0x10);
    const Error e = expect_error(bytes, ErrorCode::kFormat);
    EXPECT_THAT(e.message, HasSubstr("byte 1024: page 1 fails its CRC-32C"));
}

TEST(E57Errors, TruncatedPage) {
    std::vector<char> bytes = small_file();
    bytes.resize(bytes.size() - 100);
    const Error e = expect_error(bytes, ErrorCode::kTruncated);
    EXPECT_THAT(e.message, HasSubstr("the header announces"));
}

TEST(E57Errors, WholePagesCutOffWithAMatchingHeader) {
    std::vector<std::uint8_t> logical = logical_bytes(small_file(2000));
    logical.resize(logical.size() - 2 * e57::kPageDataBytes);  // the XML is gone
    poke<std::uint64_t>(logical, 16, (logical.size() / e57::kPageDataBytes) * e57::kPageBytes);
    const Error e = expect_error(edited(logical), ErrorCode::kTruncated);
    EXPECT_THAT(e.message, HasSubstr("the XML section"));
}

TEST(E57Errors, LyingSectionLength) {
    std::vector<std::uint8_t> logical = logical_bytes(small_file());
    poke<std::uint64_t>(logical, kSection + 8, std::uint64_t(1) << 40);
    const Error e = expect_error(edited(logical), ErrorCode::kTruncated);
    EXPECT_THAT(e.message, HasSubstr("byte 48: scan 'small': section of 1099511627776 bytes"));
}

TEST(E57Errors, LyingBytestreamBufferLength) {
    std::vector<std::uint8_t> logical = logical_bytes(small_file());
    poke<std::uint16_t>(logical, kFirstBufferLength, 0xFFFF);
    const Error e = expect_error(edited(logical), ErrorCode::kFormat);
    EXPECT_THAT(e.message, HasSubstr("byte 80: scan 'small': bytestream buffers of"));
}

TEST(E57Errors, LyingPacketLength) {
    std::vector<std::uint8_t> logical = logical_bytes(small_file());
    poke<std::uint16_t>(logical, kFirstPacket + 2, 0xFFFF);
    const Error e = expect_error(edited(logical), ErrorCode::kTruncated);
    EXPECT_THAT(e.message, HasSubstr("runs past the end of its section"));
}

TEST(E57Errors, UnknownPacketTypeAndWrongStreamCount) {
    std::vector<std::uint8_t> logical = logical_bytes(small_file());
    logical[kFirstPacket] = 7;
    EXPECT_THAT(expect_error(edited(logical), ErrorCode::kFormat).message,
                HasSubstr("unknown packet type 7"));
    logical = logical_bytes(small_file());
    poke<std::uint16_t>(logical, kFirstPacket + 4, 2);
    EXPECT_THAT(expect_error(edited(logical), ErrorCode::kFormat).message,
                HasSubstr("2 bytestreams, the prototype has 3 fields"));
}

// A count of 10^15 records would ask for petabytes: refused from the section's size.
TEST(E57Errors, HugeRecordCountIsRefusedBeforeAllocating) {
    e57::ScanSection s = small_section(50);
    s.announced_count = 1'000'000'000'000'000ull;
    const Error e = expect_error(e57::assemble_file(std::span(&s, 1)), ErrorCode::kFormat);
    EXPECT_THAT(e.message, HasSubstr("1000000000000000 records announced"));
}

TEST(E57Errors, RecordCountBeyondTheStreams) {
    e57::ScanSection s = small_section(2000);
    s.announced_count = 2001;
    const Error e = expect_error(e57::assemble_file(std::span(&s, 1)), ErrorCode::kTruncated);
    EXPECT_THAT(e.message, HasSubstr("field 'cartesianX' at 16000 of 16008 bytes"));
}

TEST(E57Errors, MalformedXml) {
    std::vector<std::uint8_t> logical = logical_bytes(small_file());
    const std::string tag = "<data3D";
    const auto at = std::search(logical.begin(), logical.end(), tag.begin(), tag.end());
    ASSERT_NE(at, logical.end());
    *(at + 1) = '=';
    const Error e = expect_error(edited(logical), ErrorCode::kFormat);
    EXPECT_THAT(e.message, HasSubstr("XML section: "));
}

TEST(E57Errors, NoScanIsEmptyAndAScanWithoutPointsReadsEmpty) {
    expect_error(e57::assemble_file({}), ErrorCode::kEmpty);
    const auto read = parse_e57(small_file(0), "none.e57");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_TRUE(read->scans[0].scan.cloud.empty());
}

TEST(E57Errors, FileErrorsNameThePath) {
    const auto read = read_e57("/nonexistent/station.e57");
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error().code, ErrorCode::kIo);
    EXPECT_THAT(read.error().message, HasSubstr("/nonexistent/station.e57"));
}

}  // namespace
}  // namespace anascan::io
