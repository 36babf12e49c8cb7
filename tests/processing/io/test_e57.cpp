// E57 reading and writing: CRC-32C, exact round trips of our own files, and the field
// encodings our writer does not use (ScaledInteger, spherical, invalid states).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "e57_test_files.hpp"

namespace anascan::io {
namespace {

using namespace e57_test;

const std::uint8_t kCheck[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};

TEST(E57Crc32c, MatchesTheCastagnoliCheckValue) {
    EXPECT_EQ(e57::crc32c(kCheck), 0xE3069283u);
    EXPECT_EQ(e57::crc32c({}), 0u);
}

void expect_same_scan(const E57Scan& a, const E57Scan& b) {
    const PointCloud& x = a.scan.cloud;
    const PointCloud& y = b.scan.cloud;
    ASSERT_EQ(x.size(), y.size());
    EXPECT_EQ(x.origin_m, y.origin_m);
    EXPECT_EQ(x.positions, y.positions);  // bit for bit
    EXPECT_EQ(x.intensity, y.intensity);
    EXPECT_EQ(x.colors, y.colors);
    EXPECT_EQ(a.grid.rows, b.grid.rows);
    EXPECT_EQ(a.grid.cols, b.grid.cols);
    EXPECT_EQ(a.grid.point_index, b.grid.point_index);
    ASSERT_EQ(a.scan.meta.T_world_scan.has_value(), b.scan.meta.T_world_scan.has_value());
    if (a.scan.meta.T_world_scan) {
        EXPECT_LT((a.scan.meta.T_world_scan->matrix() - b.scan.meta.T_world_scan->matrix())
                      .cwiseAbs()
                      .maxCoeff(),
                  1e-15);
    }
}

TEST(E57RoundTrip, TwoStationsComeBackBitForBit) {
    std::vector<E57Scan> scans{gridded_scan(7, 11, 0.0), E57Scan{}};
    scans[1].name = "ungridded";
    for (int i = 0; i < 100; ++i)
        scans[1].scan.cloud.positions.emplace_back(float(i) * 0.37f, -float(i) / 7.0f, 1e-3f);
    const auto bytes = encode_e57(scans);
    ASSERT_TRUE(bytes) << bytes.error().message;
    EXPECT_EQ(bytes->size() % 1024, 0u);
    const auto read = parse_e57(*bytes, "ours.e57");
    ASSERT_TRUE(read) << read.error().message;
    ASSERT_EQ(read->scans.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) expect_same_scan(scans[i], read->scans[i]);
    EXPECT_EQ(read->scans[0].name, scans[0].name);
    EXPECT_EQ(read->scans[1].scan.meta.id, "ours#1");
    EXPECT_EQ(read->scans[1].scan.meta.sensor_origin_scan_m, Eigen::Vector3d::Zero());
    EXPECT_FALSE(read->scans[1].scan.cloud.has_intensity());
    EXPECT_EQ(read->scans[0].invalid_count, 0u);
}

TEST(E57RoundTrip, ManyPacketsAcrossPages) {
    for (const double shift_m : {0.0, 250.0}) {
        const std::vector<E57Scan> scans{gridded_scan(301, 157, shift_m)};  // 31.5k points
        const auto bytes = encode_e57(scans);
        ASSERT_TRUE(bytes) << bytes.error().message;
        EXPECT_GT(bytes->size(), 1024u * 700u);  // many pages, and several 64 KiB packets
        const auto read = parse_e57(*bytes, "big.e57");
        ASSERT_TRUE(read) << read.error().message;
        expect_same_scan(scans[0], read->scans[0]);
    }
}

// Site coordinates (far from 0): the reader picks its own origin near the first point, so
// the local floats differ, but every world position agrees to well below a micrometre.
TEST(E57RoundTrip, SiteCoordinatesKeepTheirWorldPositions) {
    std::vector<E57Scan> scans{gridded_scan(20, 30, 0.0)};
    scans[0].scan.cloud.origin_m = Eigen::Vector3d(412345.0, 5123456.0, 312.0);
    const auto bytes = encode_e57(scans);
    ASSERT_TRUE(bytes) << bytes.error().message;
    const auto read = parse_e57(*bytes, "site.e57");
    ASSERT_TRUE(read) << read.error().message;
    const PointCloud& a = scans[0].scan.cloud;
    const PointCloud& b = read->scans[0].scan.cloud;
    ASSERT_EQ(a.size(), b.size());
    EXPECT_GT(b.origin_m.norm(), 5e6);
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        worst = std::max(worst, (a.world_position(i) - b.world_position(i)).norm());
    EXPECT_LT(worst, 1e-6);
    EXPECT_EQ(a.colors, b.colors);
}

TEST(E57RoundTrip, RejectsAGridThatDoesNotMatchTheCloud) {
    E57Scan s = gridded_scan(3, 4, 0.0);
    s.grid.point_index[1] = 0;  // point 0 in two cells
    const auto bytes = encode_e57(std::vector<E57Scan>{s});
    ASSERT_FALSE(bytes);
    EXPECT_EQ(bytes.error().code, ErrorCode::kInvalidArgument);
}

// Spherical coordinates as ScaledInteger range and Float angles; states 1 and 2 dropped.
TEST(E57Decode, SphericalScaledIntegerAndInvalidStates) {
    const std::vector<std::uint64_t> range{0, 10000, 20000, 30000, 99999};  // 0.5 + 1e-4 * raw
    const std::vector<float> azimuth{0.0f, 0.5f, -1.0f, 2.0f, 3.0f};
    const std::vector<double> elevation{0.0, 0.25, -0.5, 1.0, -1.25};
    std::vector<std::uint64_t> az_bits, el_bits;
    for (float a : azimuth) az_bits.push_back(std::bit_cast<std::uint32_t>(a));
    for (double e : elevation) el_bits.push_back(std::bit_cast<std::uint64_t>(e));
    const std::vector<std::uint64_t> state{0, 0, 2, 1, 0};
    const std::vector<std::uint64_t> intensity{0, 1005, 3, 4, 500};  // raw - (-5)
    e57::ScanSection section{.name = "sph", .record_count = 5};
    section.fields = {field(scaled_spec("sphericalRange", 0, 99999, 1e-4, 0.5), range),
                      field(float_spec("sphericalAzimuth", true), az_bits),
                      field(float_spec("sphericalElevation", false), el_bits),
                      field(integer_spec("sphericalInvalidState", 0, 2), state),
                      field(integer_spec("intensity", -5, 1000), intensity)};
    const auto read = parse_e57(e57::assemble_file(std::span(&section, 1)), "sph.e57");
    ASSERT_TRUE(read) << read.error().message;
    const E57Scan& s = read->scans[0];
    EXPECT_EQ(s.record_count, 5u);
    EXPECT_EQ(s.invalid_count, 2u);
    ASSERT_EQ(s.scan.cloud.size(), 3u);
    const std::size_t kept[] = {0, 1, 4};
    for (std::size_t i = 0; i < 3; ++i) {
        const std::size_t k = kept[i];
        const double r = 0.5 + 1e-4 * double(range[k]), a = azimuth[k], e = elevation[k];
        const Eigen::Vector3d expected(r * std::cos(e) * std::cos(a), r * std::cos(e) * std::sin(a),
                                       r * std::sin(e));
        EXPECT_LT((s.scan.cloud.world_position(i) - expected).norm(), 1e-6) << "record " << k;
        EXPECT_EQ(s.scan.cloud.intensity[i], float(std::int64_t(intensity[k]) - 5));
    }
    EXPECT_EQ(s.grid.rows, 0);
}

// Cartesian ScaledInteger with an offset, 16-bit colour scaled by colorLimits.
TEST(E57Decode, ScaledCartesianAndSixteenBitColour) {
    const std::vector<std::uint64_t> x{0, 1, 2047}, y{5, 6, 7}, z{100, 0, 3};
    const std::vector<std::uint64_t> red{0, 65535, 32768}, green{65535, 0, 0}, blue{1, 2, 3};
    e57::ScanSection section{.name = "rgb16", .record_count = 3};
    section.extra_xml =
        "<colorLimits type=\"Structure\"><colorRedMinimum type=\"Integer\">0</colorRedMinimum>"
        "<colorRedMaximum type=\"Integer\">65535</colorRedMaximum></colorLimits>";
    section.fields = {field(scaled_spec("cartesianX", -1024, 1023, 0.001, 100.0), x),
                      field(scaled_spec("cartesianY", 0, 7, 0.5, 0.0), y),
                      field(scaled_spec("cartesianZ", -50, 200, 0.01, -2.0), z),
                      field(integer_spec("colorRed", 0, 65535), red),
                      field(integer_spec("colorGreen", 0, 65535), green),
                      field(integer_spec("colorBlue", 0, 65535), blue)};
    const auto read = parse_e57(e57::assemble_file(std::span(&section, 1)), "rgb16.e57");
    ASSERT_TRUE(read) << read.error().message;
    const PointCloud& c = read->scans[0].scan.cloud;
    ASSERT_EQ(c.size(), 3u);
    EXPECT_NEAR(c.world_position(0).x(), 100.0 - 1.024, 1e-5);
    EXPECT_NEAR(c.world_position(2).x(), 100.0 + 1.023, 1e-5);
    EXPECT_NEAR(c.world_position(1).y(), 3.0, 1e-6);
    EXPECT_NEAR(c.world_position(0).z(), -2.0 + 0.5, 1e-6);
    EXPECT_EQ(c.colors[0], (Rgb8{0, 255, 0}));
    EXPECT_EQ(c.colors[1], (Rgb8{255, 0, 0}));
    EXPECT_EQ(c.colors[2].r, 128);
}

}  // namespace
}  // namespace anascan::io
