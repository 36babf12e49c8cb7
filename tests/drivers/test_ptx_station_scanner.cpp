// Terrestrial-scanner station exports (PTX) as a scanner device.
#include <gtest/gtest.h>

#include <fstream>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/ptx_station_scanner.hpp"
#include "temp_folder.hpp"

namespace anascan::drivers {
namespace {

// One station of 1 column x 2 rows, translated by (tx, 2, 3).
std::string station(int tx) {
    return "1\n2\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 0\n" + std::to_string(tx) +
           " 2 3 1\n1 2 3 0.25\n0 0 0 0.5\n";
}

class PtxStations : public ::testing::Test {
protected:
    void SetUp() override {
        std::ofstream(tmp_.path() / "b.ptx") << station(30);
        std::ofstream(tmp_.path() / "a.PTX") << station(10) << station(20);
        std::ofstream(tmp_.path() / "notes.txt") << "not a scan";
    }
    test::TempFolder tmp_;
};

TEST_F(PtxStations, DeliversEveryStationInOrderWithItsPose) {
    auto device = make_hardware_registry().open("ptx:" + tmp_.path().string());
    ASSERT_TRUE(device) << device.error().message;
    Scanner* scanner = (*device)->as_scanner();
    ASSERT_NE(scanner, nullptr);
    EXPECT_TRUE((*device)->capabilities().can_capture_scan);
    std::vector<double> fractions;
    const CaptureControl control{
        .on_progress = [&](const CaptureProgress& p) { fractions.push_back(p.fraction); }};
    for (int i = 0; i < 3; ++i) {
        auto scan = scanner->capture_scan(control);
        ASSERT_TRUE(scan) << scan.error().message;
        EXPECT_EQ(scan->meta.sequence, i);
        EXPECT_EQ(scan->meta.device_kind, DeviceKind::kTimeOfFlight);
        EXPECT_EQ(scan->meta.device_id, "ptx:" + tmp_.path().string());
        ASSERT_TRUE(scan->meta.T_world_scan);
        EXPECT_DOUBLE_EQ(scan->meta.T_world_scan->translation().x(), 10.0 * (i + 1));
        ASSERT_TRUE(scan->meta.sensor_origin_scan_m);
        EXPECT_EQ(scan->cloud.size(), 1u);  // the zero point is a missing return
    }
    EXPECT_EQ(fractions.back(), 1.0);
    auto done = scanner->capture_scan({});
    ASSERT_FALSE(done);
    EXPECT_EQ(done.error().code, ErrorCode::kEmpty);
}

TEST_F(PtxStations, CancelAndSettingsAreTypedErrors) {
    auto scanner = open_ptx_station_scanner(tmp_.path());
    ASSERT_TRUE(scanner);
    std::stop_source stop;
    stop.request_stop();
    auto cancelled = (*scanner)->capture_scan({.stop = stop.get_token()});
    ASSERT_FALSE(cancelled);
    EXPECT_EQ(cancelled.error().code, ErrorCode::kCancelled);
    auto setting = (*scanner)->configure({.angular_step_deg = 0.1});
    ASSERT_FALSE(setting);
    EXPECT_EQ(setting.error().code, ErrorCode::kInvalidArgument);
}

TEST_F(PtxStations, EmptyMissingAndCorruptFoldersAreNamed) {
    test::TempFolder other;
    EXPECT_EQ(open_ptx_station_scanner(other.path()).error().code, ErrorCode::kEmpty);
    EXPECT_EQ(open_ptx_station_scanner(other.path() / "missing").error().code, ErrorCode::kIo);
    std::ofstream(other.path() / "c.ptx") << "1\n2\n0 0 zero\n";
    auto scanner = open_ptx_station_scanner(other.path());
    ASSERT_TRUE(scanner);
    auto scan = (*scanner)->capture_scan({});
    ASSERT_FALSE(scan);
    EXPECT_NE(scan.error().message.find("c.ptx"), std::string::npos) << scan.error().message;
}

}  // namespace
}  // namespace anascan::drivers
