// Terrestrial-scanner station exports (E57) as a scanner device, and the bad exports a
// field session meets: a file that is not E57, a station without a pose, one without points.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/e57_station_scanner.hpp"
#include "anascan/processing/io/e57.hpp"
#include "temp_folder.hpp"

namespace anascan::drivers {
namespace {

using ::testing::HasSubstr;

// A station of `n` points on a line, posed at (tx, 2, 3) unless `posed` is false.
io::E57Scan station(std::string name, int n, double tx, bool posed = true) {
    io::E57Scan s;
    s.name = std::move(name);
    for (int i = 0; i < n; ++i) s.scan.cloud.positions.emplace_back(float(i), 1.0f, 2.0f);
    if (posed) s.scan.meta.T_world_scan = make_pose(Eigen::Quaterniond::Identity(), {tx, 2, 3});
    return s;
}

void write(const std::filesystem::path& path, std::vector<io::E57Scan> scans) {
    ASSERT_TRUE(io::write_e57(path, scans));
}

class E57Stations : public ::testing::Test {
protected:
    void SetUp() override {
        write(tmp_.path() / "a.e57", {station("s1", 3, 10), station("s2", 4, 20)});
        write(tmp_.path() / "b.E57", {station("s3", 5, 0, false)});
        std::ofstream(tmp_.path() / "c.e57") << "ply\nformat ascii 1.0\nend_header\n";
        write(tmp_.path() / "d.e57", {station("empty", 0, 40)});
        write(tmp_.path() / "e.e57", {station("s5", 6, 50)});
        std::ofstream(tmp_.path() / "notes.txt") << "not a scan";
    }
    test::TempFolder tmp_;
};

TEST_F(E57Stations, DeliversStationsAndNamesEachBadExportThenGoesOn) {
    auto device = make_hardware_registry().open("e57:" + tmp_.path().string());
    ASSERT_TRUE(device) << device.error().message;
    Scanner* scanner = (*device)->as_scanner();
    ASSERT_NE(scanner, nullptr);
    std::vector<std::string> messages;
    const CaptureControl control{
        .on_progress = [&](const CaptureProgress& p) { messages.push_back(p.stage); }};
    const double tx[] = {10, 20};
    for (int i = 0; i < 2; ++i) {
        auto scan = scanner->capture_scan(control);
        ASSERT_TRUE(scan) << scan.error().message;
        EXPECT_EQ(scan->meta.sequence, i);
        EXPECT_EQ(scan->meta.device_kind, DeviceKind::kTimeOfFlight);
        ASSERT_TRUE(scan->meta.T_world_scan);
        EXPECT_DOUBLE_EQ(scan->meta.T_world_scan->translation().x(), tx[i]);
        EXPECT_EQ(scan->meta.sensor_origin_scan_m, Eigen::Vector3d::Zero());
        EXPECT_EQ(scan->cloud.size(), std::size_t(3 + i));
    }
    auto unposed = scanner->capture_scan(control);  // a station without a pose still comes
    ASSERT_TRUE(unposed) << unposed.error().message;
    EXPECT_FALSE(unposed->meta.T_world_scan);
    EXPECT_THAT(messages.back(), HasSubstr("no pose in the export"));
    auto not_e57 = scanner->capture_scan(control);
    ASSERT_FALSE(not_e57);
    EXPECT_EQ(not_e57.error().code, ErrorCode::kFormat);
    EXPECT_THAT(not_e57.error().message, HasSubstr("c.e57: byte 0: not an E57 file"));
    auto empty = scanner->capture_scan(control);
    ASSERT_FALSE(empty);
    EXPECT_EQ(empty.error().code, ErrorCode::kFormat);
    EXPECT_THAT(empty.error().message, HasSubstr("d.e57: station 'empty' holds no points"));
    auto last = scanner->capture_scan(control);
    ASSERT_TRUE(last) << last.error().message;
    EXPECT_EQ(last->meta.sequence, 3);
    EXPECT_EQ(last->cloud.size(), 6u);
    auto done = scanner->capture_scan({});
    ASSERT_FALSE(done);
    EXPECT_EQ(done.error().code, ErrorCode::kEmpty);
}

TEST_F(E57Stations, MissingAndEmptyFoldersAreNamed) {
    test::TempFolder other;
    EXPECT_EQ(open_e57_station_scanner(other.path()).error().code, ErrorCode::kEmpty);
    const auto missing = open_e57_station_scanner(other.path() / "missing");
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::kIo);
    EXPECT_THAT(missing.error().message, HasSubstr("missing"));
}

}  // namespace
}  // namespace anascan::drivers
