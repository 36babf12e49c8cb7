// Recording a scanner and playing its scans back.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "anascan/drivers/device_registry.hpp"
#include "anascan/drivers/ptx_station_scanner.hpp"
#include "anascan/drivers/recording.hpp"
#include "temp_folder.hpp"

namespace anascan::drivers {
namespace {

void write_stations(const std::filesystem::path& folder, int count) {
    std::filesystem::create_directories(folder);
    for (int i = 0; i < count; ++i) {
        std::ofstream(folder / ("s" + std::to_string(i) + ".ptx"))
            << "1\n2\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 1 0 0\n-1 0 0 0\n0 0 1 0\n"
            << i << " 2 3 1\n1 2 3 0.25\n1 2 3.5 0.5\n";
    }
}

std::vector<Scan> record_stations(const std::filesystem::path& ptx,
                                  const std::filesystem::path& rec) {
    auto ptx_scanner = open_ptx_station_scanner(ptx);
    EXPECT_TRUE(ptx_scanner);
    auto recorder = record_scanner(std::move(*ptx_scanner), {.folder = rec});
    EXPECT_TRUE(recorder) << recorder.error().message;
    std::vector<Scan> scans;
    while (auto scan = (*recorder)->capture_scan({})) scans.push_back(std::move(*scan));
    return scans;
}

TEST(ScanRecording, PlaybackReturnsTheSameScansAndMetadata) {
    test::TempFolder tmp;
    write_stations(tmp.path() / "ptx", 3);
    const std::vector<Scan> recorded = record_stations(tmp.path() / "ptx", tmp.path() / "rec");
    ASSERT_EQ(recorded.size(), 3u);
    auto device = make_hardware_registry().open("playback:" + (tmp.path() / "rec").string());
    ASSERT_TRUE(device) << device.error().message;
    Scanner* player = (*device)->as_scanner();
    ASSERT_NE(player, nullptr);
    EXPECT_EQ(player->info().model, "PTX station exports (playback)");
    for (const Scan& original : recorded) {
        auto scan = player->capture_scan({});
        ASSERT_TRUE(scan) << scan.error().message;
        EXPECT_EQ(scan->meta.id, original.meta.id);
        EXPECT_EQ(scan->meta.sequence, original.meta.sequence);
        EXPECT_EQ(scan->meta.device_kind, DeviceKind::kTimeOfFlight);
        ASSERT_TRUE(scan->meta.T_world_scan);
        EXPECT_TRUE(scan->meta.T_world_scan->isApprox(*original.meta.T_world_scan, 1e-12));
        ASSERT_EQ(scan->cloud.size(), original.cloud.size());
        EXPECT_EQ(scan->cloud.positions[1], original.cloud.positions[1]);
    }
    EXPECT_EQ(player->capture_scan({}).error().code, ErrorCode::kEmpty);
}

TEST(ScanRecording, AScanWithoutItsMetadataIsNotPlayedBack) {
    test::TempFolder tmp;
    write_stations(tmp.path() / "ptx", 2);
    record_stations(tmp.path() / "ptx", tmp.path() / "rec");
    std::filesystem::remove(tmp.path() / "rec/scans/000001.json");  // crash before the marker
    auto player = open_scan_playback({.folder = tmp.path() / "rec"});
    ASSERT_TRUE(player);
    EXPECT_TRUE((*player)->capture_scan({}));
    EXPECT_EQ((*player)->capture_scan({}).error().code, ErrorCode::kEmpty);
    EXPECT_EQ(open_playback({.folder = tmp.path() / "rec"}).error().code, ErrorCode::kUnsupported);
}

// A JSON float where an integer belongs: converting 1.7e20 to a 64-bit integer is undefined,
// so the record is refused with the file's name (found by fuzz_recording).
TEST(ScanRecording, AnOutOfRangeTimeIsRefusedWithTheFileNamed) {
    test::TempFolder tmp;
    write_stations(tmp.path() / "ptx", 1);
    record_stations(tmp.path() / "ptx", tmp.path() / "rec");
    const std::filesystem::path record = tmp.path() / "rec/scans/000000.json";
    std::ostringstream read;
    read << std::ifstream(record).rdbuf();
    std::string text = read.str();
    const std::size_t at = text.find("\"time_ns\":");
    ASSERT_NE(at, std::string::npos) << text;
    const std::size_t end = text.find_first_of(",}", at);
    text.replace(at, end - at, "\"time_ns\": 1.7e20");
    std::ofstream(record, std::ios::trunc) << text;
    auto player = open_scan_playback({.folder = tmp.path() / "rec"});
    ASSERT_TRUE(player) << player.error().message;
    const auto scan = (*player)->capture_scan({});
    ASSERT_FALSE(scan);
    EXPECT_EQ(scan.error().code, ErrorCode::kFormat);
    EXPECT_NE(scan.error().message.find(record.string()), std::string::npos)
        << scan.error().message;
    EXPECT_NE(scan.error().message.find("integer"), std::string::npos) << scan.error().message;
}

}  // namespace
}  // namespace anascan::drivers
