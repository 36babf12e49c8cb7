// Broken and hostile PLY files: each fails with the right code and a message that starts
// with the source name, then says where ("line N" / "byte N") and what was wrong.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "anascan/processing/io/ply.hpp"

namespace anascan::io {
namespace {

constexpr const char* kName = "broken.ply";

Expected<PlyData> parse(const std::string& text) {
    return parse_ply(std::span<const char>(text.data(), text.size()), kName);
}

// Asserts the failure code and that the message reads "broken.ply: <location>: ...<what>".
void expect_error(const Expected<PlyData>& result, ErrorCode code, const std::string& location,
                  const std::string& what) {
    ASSERT_FALSE(result) << "parsed a broken file";
    const std::string& message = result.error().message;
    EXPECT_EQ(result.error().code, code) << message;
    EXPECT_EQ(message.rfind(std::string(kName) + ": " + location + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
}

const std::string kXyz = "property float x\nproperty float y\nproperty float z\n";

std::string binary_header(int vertices) {
    return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) +
           "\n" + kXyz + "end_header\n";
}

std::string floats(std::initializer_list<float> values) {
    std::string out;
    for (const float v : values) out.append(reinterpret_cast<const char*>(&v), sizeof(v));
    return out;
}

TEST(PlyErrors, MissingMagic) {
    expect_error(parse("PLY\nformat ascii 1.0\nend_header\n"), ErrorCode::kFormat, "line 1",
                 "not a PLY file");
}

// A 0-byte file is named as what it is, not as a file of another format.
TEST(PlyErrors, EmptyFile) {
    const auto result = parse("");
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, ErrorCode::kEmpty);
    EXPECT_EQ(result.error().message, std::string(kName) + ": empty file (0 bytes)");
}

TEST(PlyErrors, UnknownFormat) {
    expect_error(parse("ply\nformat binary_middle_endian 1.0\nend_header\n"),
                 ErrorCode::kUnsupported, "line 2", "binary_middle_endian");
}

TEST(PlyErrors, TruncatedHeaderWithoutEndHeader) {
    expect_error(parse("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"),
                 ErrorCode::kTruncated, "line 4", "end_header");
}

TEST(PlyErrors, UnknownPropertyType) {
    expect_error(parse("ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\n"
                       "end_header\n1\n"),
                 ErrorCode::kUnsupported, "line 4", "float128");
}

TEST(PlyErrors, UnknownHeaderKeyword) {
    expect_error(parse("ply\nformat ascii 1.0\nvertices 3\nend_header\n"), ErrorCode::kFormat,
                 "line 3", "vertices");
}

TEST(PlyErrors, BinaryVertexCountLargerThanData) {
    // Header announces 4 vertices; the data holds 2 and a half.
    const std::string header = binary_header(4);
    const std::string file = header + floats({1, 2, 3, 4, 5, 6, 7, 8});
    const std::string offset = std::to_string(header.size() + 24);
    expect_error(parse(file), ErrorCode::kTruncated, "byte " + offset,
                 "vertex 2 of 4: file ends early (truncated; the header announces 4 vertices)");
}

TEST(PlyErrors, AsciiVertexCountLargerThanData) {
    const std::string file =
        "ply\nformat ascii 1.0\nelement vertex 30\n" + kXyz + "end_header\n1 2 3\n4 5 6\n";
    expect_error(parse(file), ErrorCode::kTruncated, "line 10", "vertex 2 of 30: file ends early");
}

TEST(PlyErrors, AsciiShortLine) {
    const std::string file =
        "ply\nformat ascii 1.0\nelement vertex 3\n" + kXyz + "end_header\n1 2 3\n4 5\n7 8 9\n";
    expect_error(parse(file), ErrorCode::kFormat, "line 9", "vertex 1 of 3: property 'z'");
}

TEST(PlyErrors, NonNumericAsciiValue) {
    const std::string file =
        "ply\nformat ascii 1.0\nelement vertex 2\n" + kXyz + "end_header\n1 2 3\r\n4 five 6\r\n";
    expect_error(parse(file), ErrorCode::kFormat, "line 9",
                 "vertex 1 of 2: property 'y': 'five' is not a number");
}

TEST(PlyErrors, AsciiValueOutOfRangeForItsType) {
    const std::string file = "ply\nformat ascii 1.0\nelement vertex 1\n" + kXyz +
                             "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                             "end_header\n1 2 3 300 0 0\n";
    expect_error(parse(file), ErrorCode::kFormat, "line 11", "'300' is out of range for uchar");
}

TEST(PlyErrors, AsciiExtraValueOnALine) {
    const std::string file =
        "ply\nformat ascii 1.0\nelement vertex 1\n" + kXyz + "end_header\n1 2 3 4\n";
    expect_error(parse(file), ErrorCode::kFormat, "line 8", "unexpected value '4'");
}

TEST(PlyErrors, AsciiFaceIndexOutOfRange) {
    const std::string file = "ply\nformat ascii 1.0\nelement vertex 3\n" + kXyz +
                             "element face 2\nproperty list uchar int vertex_indices\n"
                             "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n";
    expect_error(parse(file), ErrorCode::kFormat, "line 14",
                 "face 1 of 2: vertex index 3 out of range (the file has 3 vertices)");
}

TEST(PlyErrors, BinaryFaceIndexOutOfRange) {
    std::string file = "ply\nformat binary_little_endian 1.0\nelement vertex 1\n" + kXyz +
                       "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    file += floats({0, 0, 0});
    file += '\3';
    const std::size_t second_index = file.size() + 4;
    for (const std::int32_t i : {0, -1, 0}) file.append(reinterpret_cast<const char*>(&i), 4);
    expect_error(parse(file), ErrorCode::kFormat, "byte " + std::to_string(second_index),
                 "face 0 of 1: vertex index -1 out of range");
}

TEST(PlyErrors, FaceWithTooFewIndices) {
    const std::string file = "ply\nformat ascii 1.0\nelement vertex 3\n" + kXyz +
                             "element face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n";
    expect_error(parse(file), ErrorCode::kFormat, "line 13", "at least 3 vertex indices");
}

TEST(PlyErrors, AbsurdCountInHeader) {
    const std::string file = "ply\nformat binary_little_endian 1.0\nelement vertex 99999999999\n" +
                             kXyz + "end_header\n" + floats({1, 2, 3});
    expect_error(parse(file), ErrorCode::kFormat, "line 3", "count 99999999999 is absurd");
}

// Parses a header announcing 2e9 vertices (24 GB) over a few bytes of data.
bool huge_count_is_refused(bool binary) {
    const std::string file = std::string("ply\nformat ") +
                             (binary ? "binary_little_endian" : "ascii") +
                             " 1.0\nelement vertex 2000000000\n" + kXyz +
                             "element range_grid 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n" +
                             (binary ? floats({1, 2, 3}) : "1 2 3\n");
    const Expected<PlyData> result = parse(file);
    return !result && result.error().code == ErrorCode::kTruncated &&
           result.error().message.find("of 2000000000: file ends early") != std::string::npos;
}

// Runs in a child limited to 1 GiB of address space: reserving for the announced count
// would throw std::bad_alloc and end the child abnormally.
[[noreturn]] void check_huge_count_with_little_memory(bool binary) {
    rlimit limit{};
    limit.rlim_cur = limit.rlim_max = 1ul << 30;
    ::setrlimit(RLIMIT_AS, &limit);
    std::exit(huge_count_is_refused(binary) ? 0 : 1);
}

TEST(PlyErrors, CountFarLargerThanTheFileFailsWithoutAllocating) {
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer reserves terabytes of shadow address space: no child can run under a
    // 1 GiB RLIMIT_AS. The refusal itself is still tested, without the limit, below.
    EXPECT_TRUE(huge_count_is_refused(true));
    EXPECT_TRUE(huge_count_is_refused(false));
    GTEST_SKIP() << "RLIMIT_AS cannot be set under AddressSanitizer";
#endif
    EXPECT_EXIT(check_huge_count_with_little_memory(true), ::testing::ExitedWithCode(0), "");
    EXPECT_EXIT(check_huge_count_with_little_memory(false), ::testing::ExitedWithCode(0), "");
}

TEST(PlyErrors, ListCountExceedingData) {
    std::string file = "ply\nformat binary_little_endian 1.0\nelement vertex 1\n" + kXyz +
                       "element face 1\nproperty list uint int vertex_indices\nend_header\n";
    file += floats({0, 0, 0});
    const std::size_t count_at = file.size();
    const std::uint32_t count = 4000000000u;
    file.append(reinterpret_cast<const char*>(&count), 4);
    file += std::string(12, '\0');
    expect_error(parse(file), ErrorCode::kTruncated, "byte " + std::to_string(count_at),
                 "face 0 of 1: list 'vertex_indices' announces 4000000000 entries");
}

TEST(PlyErrors, AsciiTrailingGarbage) {
    const std::string file =
        "ply\nformat ascii 1.0\nelement vertex 1\n" + kXyz + "end_header\n1 2 3\n\n4 5 6\n";
    expect_error(parse(file), ErrorCode::kFormat, "line 10", "after the last element");
}

TEST(PlyErrors, BinaryTrailingGarbage) {
    const std::string header = binary_header(1);
    const std::string file = header + floats({1, 2, 3}) + "junk";
    expect_error(parse(file), ErrorCode::kFormat, "byte " + std::to_string(header.size() + 12),
                 "4 bytes of unexpected data after the last element");
}

TEST(PlyErrors, NonFiniteOriginComment) {
    const std::string file =
        "ply\nformat ascii 1.0\ncomment anascan origin_m 1 nan 2\n"
        "element vertex 0\n" +
        kXyz + "end_header\n";
    expect_error(parse(file), ErrorCode::kFormat, "line 3", "origin_m");
}

TEST(PlyErrors, RangeGridSizeDisagreesWithObjInfo) {
    const std::string file =
        "ply\nformat ascii 1.0\nobj_info num_cols 2\nobj_info num_rows 2\n"
        "element vertex 0\n" +
        kXyz +
        "element range_grid 3\nproperty list uchar int vertex_indices\n"
        "end_header\n0\n0\n0\n";
    expect_error(parse(file), ErrorCode::kFormat, "line 12", "num_rows * num_cols");
}

TEST(PlyErrors, VertexWithoutCoordinates) {
    const std::string file =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
        "end_header\n1\n";
    expect_error(parse(file), ErrorCode::kUnsupported, "line 6", "no x, y and z");
}

TEST(PlyErrors, ReadingAMissingFileNamesIt) {
    const Expected<PlyData> result = read_ply("/nonexistent/dir/scan.ply");
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, ErrorCode::kIo);
    EXPECT_NE(result.error().message.find("scan.ply"), std::string::npos);
}

}  // namespace
}  // namespace anascan::io
