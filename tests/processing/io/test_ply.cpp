#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "anascan/processing/io/ply.hpp"

namespace anascan::io {
namespace {

namespace fs = std::filesystem;

std::span<const char> span_of(const std::string& text) { return {text.data(), text.size()}; }

// Bitwise comparison, so that -0.0 vs 0.0 and NaN payloads count as different.
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// A cloud with every attribute, including awkward floats (fixed seed).
PointCloud full_cloud(std::size_t n) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> coord(-1000.0f, 1000.0f);
    std::uniform_int_distribution<int> byte(0, 255);
    PointCloud cloud;
    cloud.origin_m = {452123.123456789012, 5412345.98765432101, -12.000000000000123};
    for (std::size_t i = 0; i < n; ++i) {
        cloud.positions.emplace_back(coord(rng), coord(rng) * 1e-7f, coord(rng) * 1e20f);
        cloud.normals.emplace_back(
            Eigen::Vector3f(coord(rng), coord(rng), coord(rng)).normalized());
        cloud.colors.push_back(Rgb8{static_cast<std::uint8_t>(byte(rng)),
                                    static_cast<std::uint8_t>(byte(rng)),
                                    static_cast<std::uint8_t>(byte(rng))});
        cloud.intensity.push_back(coord(rng));
        cloud.confidence.push_back(coord(rng) / 1000.0f);
    }
    cloud.positions[0] = {-0.0f, std::numeric_limits<float>::denorm_min(),
                          std::numeric_limits<float>::max()};
    cloud.positions[1] = {std::numeric_limits<float>::lowest(), 1.0f / 3.0f, 0.1f};
    return cloud;
}

/// With an origin the file holds absolute double coordinates (origin + local), so local
/// positions come back within the double rounding of the absolute value (~1e-9 m here).
void expect_same_positions(const PointCloud& expected, const PointCloud& actual) {
    if (expected.origin_m == Eigen::Vector3d::Zero()) {
        EXPECT_TRUE(same_bits(expected.positions, actual.positions));
        return;
    }
    ASSERT_EQ(expected.size(), actual.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            const double a = expected.positions[i][k], b = actual.positions[i][k];
            ASSERT_LE(std::abs(a - b), 1e-8 + 1e-7 * std::abs(a)) << "point " << i;
        }
    }
}

void expect_same_cloud(const PointCloud& expected, const PointCloud& actual) {
    EXPECT_EQ(expected.origin_m, actual.origin_m);
    expect_same_positions(expected, actual);
    EXPECT_TRUE(same_bits(expected.normals, actual.normals));
    EXPECT_TRUE(expected.colors == actual.colors);
    EXPECT_TRUE(same_bits(expected.intensity, actual.intensity));
    EXPECT_TRUE(same_bits(expected.confidence, actual.confidence));
}

class PlyRoundTrip : public ::testing::TestWithParam<PlyFormat> {};

TEST(Ply, ACloudWithAnOriginIsWrittenInAbsoluteCoordinatesOtherProgramsRead) {
    PointCloud cloud;
    cloud.origin_m = {452123.25, 5412345.5, 12.0};
    cloud.positions = {{0.5f, -0.25f, 0.125f}};
    const std::vector<char> bytes = serialize_ply(cloud, {}, {.format = PlyFormat::kAscii});
    const std::string text(bytes.begin(), bytes.end());
    EXPECT_NE(text.find("property double x\nproperty double y\nproperty double z\n"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("end_header\n452123.75 5412345.25 12.125\n"), std::string::npos) << text;
    const Expected<PlyData> read = parse_ply(bytes, "origin.ply");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->cloud.origin_m, cloud.origin_m);
    EXPECT_EQ(read->cloud.positions[0], cloud.positions[0]);
}

TEST_P(PlyRoundTrip, CloudWithEveryAttributeIsBitExact) {
    const PointCloud cloud = full_cloud(500);
    const std::vector<char> bytes =
        serialize_ply(cloud, {}, {.format = GetParam(), .comments = {"scanned by test"}});
    const Expected<PlyData> read = parse_ply(bytes, "roundtrip.ply");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->format, GetParam());
    expect_same_cloud(cloud, read->cloud);
    EXPECT_TRUE(read->triangles.empty());
    ASSERT_EQ(read->comments.size(), 1u);
    EXPECT_EQ(read->comments[0], "scanned by test");
}

TEST_P(PlyRoundTrip, MeshIsBitExact) {
    Mesh mesh;
    mesh.vertices = full_cloud(50);
    mesh.vertices.origin_m.setZero();
    mesh.vertices.normals.clear();
    mesh.vertices.confidence.clear();
    for (int i = 0; i + 2 < 50; ++i) mesh.triangles.emplace_back(i, i + 1, 49 - i);
    const std::vector<char> bytes =
        serialize_ply(mesh.vertices, mesh.triangles, {.format = GetParam(), .comments = {}});
    const Expected<PlyData> read = parse_ply(bytes, "mesh.ply");
    ASSERT_TRUE(read) << read.error().message;
    expect_same_cloud(mesh.vertices, read->cloud);
    EXPECT_EQ(read->triangles, mesh.triangles);
}

TEST_P(PlyRoundTrip, ExtraVertexScalarsAreReadBackByName) {
    PointCloud cloud = full_cloud(40);
    PlyScalarProperty support{.name = "support_distance_m"}, cls{.name = "interpolated"};
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        support.values.push_back(0.001f * float(i));
        cls.values.push_back(float(i % 3 == 0));
    }
    const std::vector<char> bytes =
        serialize_ply(cloud, {}, {.format = GetParam(), .vertex_scalars = {support, cls}});
    const Expected<PlyData> read = parse_ply(bytes, "scalars.ply");
    ASSERT_TRUE(read) << read.error().message;
    expect_same_cloud(cloud, read->cloud);
    ASSERT_EQ(read->vertex_scalars.size(), 2u);
    EXPECT_EQ(read->vertex_scalars[0].name, "support_distance_m");
    EXPECT_EQ(read->vertex_scalars[0].values, support.values);
    EXPECT_EQ(read->vertex_scalars[1].name, "interpolated");
    EXPECT_EQ(read->vertex_scalars[1].values, cls.values);
}

TEST(Ply, AtMostEightUnknownScalarsAreKept) {
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
        "property float y\nproperty float z\n";
    std::string row = "1 2 3";
    for (int k = 0; k < 10; ++k) {
        text += "property uchar s" + std::to_string(k) + "\n";
        row += " " + std::to_string(k);
    }
    text += "end_header\n" + row + "\n";
    const Expected<PlyData> read = parse_ply(std::span(text.data(), text.size()), "many.ply");
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_EQ(read->vertex_scalars.size(), 8u);
    EXPECT_EQ(read->vertex_scalars[7].name, "s7");
    EXPECT_EQ(read->vertex_scalars[7].values, std::vector<float>{7.0f});
}

TEST_P(PlyRoundTrip, NanAndInfinityAreKept) {
    PointCloud cloud;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    cloud.positions = {{nan, inf, -inf}, {1.0f, 2.0f, 3.0f}};
    const Expected<PlyData> read =
        parse_ply(serialize_ply(cloud, {}, {.format = GetParam(), .comments = {}}), "nan.ply");
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_EQ(read->cloud.size(), 2u);
    EXPECT_TRUE(std::isnan(read->cloud.positions[0].x()));
    EXPECT_EQ(read->cloud.positions[0].y(), inf);
    EXPECT_EQ(read->cloud.positions[0].z(), -inf);
    EXPECT_EQ(read->cloud.positions[1], Eigen::Vector3f(1.0f, 2.0f, 3.0f));
}

TEST_P(PlyRoundTrip, EmptyCloud) {
    const Expected<PlyData> read =
        parse_ply(serialize_ply(PointCloud{}, {}, {.format = GetParam(), .comments = {}}), "e");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_TRUE(read->cloud.empty());
}

INSTANTIATE_TEST_SUITE_P(Ply, PlyRoundTrip,
                         ::testing::Values(PlyFormat::kAscii, PlyFormat::kBinaryLittleEndian,
                                           PlyFormat::kBinaryBigEndian));

TEST(Ply, WriteAndReadFileWithMesh) {
    const fs::path dir = fs::path(ANASCAN_BINARY_DIR) / "test-tmp" / "ply";
    fs::create_directories(dir);
    Mesh mesh;
    mesh.vertices.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}};
    ASSERT_TRUE(write_ply(dir / "tri.ply", mesh));
    const Expected<PlyData> read = read_ply(dir / "tri.ply");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->cloud.positions, mesh.vertices.positions);
    EXPECT_EQ(read->triangles, mesh.triangles);
    fs::remove_all(dir);
}

TEST(Ply, WritingAnInconsistentCloudIsRefused) {
    PointCloud cloud;
    cloud.positions = {{0, 0, 0}, {1, 0, 0}};
    cloud.intensity = {1.0f};
    const Expected<void> written = write_ply(fs::path(ANASCAN_BINARY_DIR) / "bad.ply", cloud);
    ASSERT_FALSE(written);
    EXPECT_EQ(written.error().code, ErrorCode::kInvalidArgument);
}

TEST(Ply, AsciiPropertiesInAnyOrderWithCrlfAndAliases) {
    const std::string text =
        "ply\r\nformat ascii 1.0\r\ncomment hello\r\nelement vertex 2\r\n"
        "property uchar g\r\nproperty float z\r\nproperty int extra\r\nproperty uchar r\r\n"
        "property float nz\r\nproperty float x\r\nproperty float ny\r\nproperty uchar b\r\n"
        "property float y\r\nproperty float nx\r\nproperty float confidence\r\n"
        "property float intensity\r\nend_header\r\n"
        "10 3 -7 20 1 1.5 0 30 2.5 0 0.5 100\r\n"
        "\r\n"
        "11 -3e2 7 21 0 +4 1 31 5 0 1 200\r\n";
    const Expected<PlyData> read = parse_ply(span_of(text), "order.ply");
    ASSERT_TRUE(read) << read.error().message;
    const PointCloud& c = read->cloud;
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c.positions[0], Eigen::Vector3f(1.5f, 2.5f, 3.0f));
    EXPECT_EQ(c.positions[1], Eigen::Vector3f(4.0f, 5.0f, -300.0f));
    EXPECT_EQ(c.normals[0], Eigen::Vector3f(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(c.normals[1], Eigen::Vector3f(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(c.colors[0], (Rgb8{20, 10, 30}));
    EXPECT_EQ(c.colors[1], (Rgb8{21, 11, 31}));
    EXPECT_EQ(c.confidence, (std::vector<float>{0.5f, 1.0f}));
    EXPECT_EQ(c.intensity, (std::vector<float>{100.0f, 200.0f}));
    EXPECT_EQ(read->comments, std::vector<std::string>{"hello"});
}

// Encodes `value` as a PLY scalar of `type` in the given byte order.
void put(std::string& out, const std::string& type, double value, bool big_endian) {
    char bytes[8];
    std::size_t n = 0;
    const auto copy = [&](auto v) {
        n = sizeof(v);
        std::memcpy(bytes, &v, n);
    };
    if (type == "char") copy(static_cast<std::int8_t>(value));
    if (type == "uchar") copy(static_cast<std::uint8_t>(value));
    if (type == "short") copy(static_cast<std::int16_t>(value));
    if (type == "ushort") copy(static_cast<std::uint16_t>(value));
    if (type == "int") copy(static_cast<std::int32_t>(value));
    if (type == "uint") copy(static_cast<std::uint32_t>(value));
    if (type == "float") copy(static_cast<float>(value));
    if (type == "double") copy(value);
    if (big_endian == (std::endian::native == std::endian::little)) std::reverse(bytes, bytes + n);
    out.append(bytes, n);
}

TEST(Ply, BinaryTypedPropertiesInBothByteOrders) {
    for (const bool big : {false, true}) {
        std::string file = std::string("ply\nformat ") +
                           (big ? "binary_big_endian" : "binary_little_endian") +
                           " 1.0\nelement vertex 2\nproperty double z\nproperty int8 extra\n"
                           "property int y\nproperty float32 red\nproperty uchar x\n"
                           "property ushort green\nproperty float64 blue\nend_header\n";
        for (int i = 0; i < 2; ++i) {
            put(file, "double", 0.1 + i, big);
            put(file, "char", -5, big);
            put(file, "int", -70000 * (i + 1), big);
            put(file, "float", 0.5 * i, big);
            put(file, "uchar", 200 + i, big);
            put(file, "ushort", 65535 * i, big);
            put(file, "double", 2.0, big);  // above 1: clamps to 255
        }
        const Expected<PlyData> read = parse_ply(span_of(file), "typed.ply");
        ASSERT_TRUE(read) << read.error().message;
        ASSERT_EQ(read->cloud.size(), 2u);
        EXPECT_EQ(read->cloud.positions[0], Eigen::Vector3f(200.0f, -70000.0f, 0.1f));
        EXPECT_EQ(read->cloud.positions[1], Eigen::Vector3f(201.0f, -140000.0f, 1.1f));
        EXPECT_EQ(read->cloud.colors[0], (Rgb8{0, 0, 255}));
        EXPECT_EQ(read->cloud.colors[1], (Rgb8{128, 255, 255}));
    }
}

TEST(Ply, HandBuiltBigEndianBytes) {
    std::string file =
        "ply\nformat binary_big_endian 1.0\nelement vertex 1\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n";
    // 1.0f, -2.0f, 0.5f as big-endian IEEE 754.
    const unsigned char body[] = {0x3F, 0x80, 0, 0, 0xC0, 0x00, 0, 0, 0x3F, 0x00, 0, 0};
    file.append(reinterpret_cast<const char*>(body), sizeof(body));
    const Expected<PlyData> read = parse_ply(span_of(file), "be.ply");
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_EQ(read->cloud.size(), 1u);
    EXPECT_EQ(read->cloud.positions[0], Eigen::Vector3f(1.0f, -2.0f, 0.5f));
    EXPECT_EQ(read->format, PlyFormat::kBinaryBigEndian);
}

TEST(Ply, BinaryVertexWithListUsesTheGenericPathAndSkipsElements) {
    std::string file =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
        "property float x\nproperty list uchar short tags\nproperty float y\n"
        "property float z\nelement edge 1\nproperty int a\nproperty int b\n"
        "element face 2\nproperty list ushort uint vertex_index\nend_header\n";
    for (int i = 0; i < 3; ++i) {
        put(file, "float", i, false);
        put(file, "uchar", 2, false);
        put(file, "short", 7, false);
        put(file, "short", 8, false);
        put(file, "float", 10 + i, false);
        put(file, "float", 20 + i, false);
    }
    put(file, "int", 0, false);
    put(file, "int", 1, false);
    put(file, "ushort", 4, false);  // a quad: two triangles
    for (const double v : {0.0, 1.0, 2.0, 1.0}) put(file, "uint", v, false);
    put(file, "ushort", 3, false);
    for (const double v : {2.0, 1.0, 0.0}) put(file, "uint", v, false);
    const Expected<PlyData> read = parse_ply(span_of(file), "generic.ply");
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_EQ(read->cloud.size(), 3u);
    EXPECT_EQ(read->cloud.positions[2], Eigen::Vector3f(2.0f, 12.0f, 22.0f));
    EXPECT_FALSE(read->cloud.has_normals());
    EXPECT_EQ(read->skipped_elements, std::vector<std::string>{"edge"});
    const std::vector<Eigen::Vector3i> expected{{0, 1, 2}, {0, 2, 1}, {2, 1, 0}};
    EXPECT_EQ(read->triangles, expected);
}

TEST(Ply, AsciiPolygonsAreFanTriangulated) {
    const std::string text =
        "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty uchar flags\n"
        "property list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 2\n7 5 0 1 2 3 4\n0 3 4 3 2";
    const Expected<PlyData> read = parse_ply(span_of(text), "poly.ply");
    ASSERT_TRUE(read) << read.error().message;
    const std::vector<Eigen::Vector3i> expected{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {4, 3, 2}};
    EXPECT_EQ(read->triangles, expected);
}

TEST(Ply, RangeGridAscii) {
    const std::string text =
        "ply\nformat ascii 1.0\nobj_info num_cols 3\nobj_info num_rows 2\nelement vertex 3\n"
        "property float x\nproperty float y\nproperty float z\nelement range_grid 6\n"
        "property list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 1 1\n2 2 2\n1 0\n0\n1 1\n0\n0\n1 2\n";
    const Expected<PlyData> read = parse_ply(span_of(text), "grid.ply");
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_TRUE(read->grid.has_value());
    EXPECT_EQ(read->grid->rows, 2);
    EXPECT_EQ(read->grid->cols, 3);
    const std::vector<std::int32_t> expected{
        0, RangeGrid::kNoSample, 1, RangeGrid::kNoSample, RangeGrid::kNoSample, 2};
    EXPECT_EQ(read->grid->point_index, expected);
    EXPECT_EQ(read->grid->at(1, 2), 2);
    EXPECT_EQ(read->comments,
              (std::vector<std::string>{"obj_info num_cols 3", "obj_info num_rows 2"}));
}

TEST(Ply, RangeGridBinaryBigEndian) {
    std::string file =
        "ply\nformat binary_big_endian 1.0\nobj_info num_cols 2\n"
        "obj_info num_rows 1\nelement vertex 1\nproperty float x\n"
        "property float y\nproperty float z\nelement range_grid 2\n"
        "property list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 3; ++i) put(file, "float", 1.0, true);
    put(file, "uchar", 0, true);
    put(file, "uchar", 1, true);
    put(file, "int", 0, true);
    const Expected<PlyData> read = parse_ply(span_of(file), "grid_be.ply");
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_TRUE(read->grid.has_value());
    EXPECT_EQ(read->grid->point_index, (std::vector<std::int32_t>{RangeGrid::kNoSample, 0}));
}

TEST(Ply, AsciiNanAndInfinityAreKept) {
    const std::string text =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
        "property double y\nproperty float z\nend_header\nnan -inf 1e-50\n";
    const Expected<PlyData> read = parse_ply(span_of(text), "nan.ply");
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_TRUE(std::isnan(read->cloud.positions[0].x()));
    EXPECT_EQ(read->cloud.positions[0].y(), -std::numeric_limits<float>::infinity());
    EXPECT_EQ(read->cloud.positions[0].z(), 0.0f);
}

}  // namespace
}  // namespace anascan::io
