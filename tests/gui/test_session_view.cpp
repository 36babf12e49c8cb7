// The session as the field app shows it: rows from ScanRecords, the stored coverage JSON,
// the group drawn, the crash-check summary.
#include <gtest/gtest.h>

#include "anascan/gui/scan_colors.hpp"
#include "anascan/gui/scan_preview.hpp"
#include "anascan/gui/session_view.hpp"
#include "anascan/processing/coverage/coverage.hpp"

namespace {

using anascan::Pose;
using anascan::acquisition::ScanRecord;
using anascan::acquisition::ScanState;
namespace gui = anascan::gui;

ScanRecord record(std::int64_t seq, ScanState state, int group, bool with_pose = true) {
    ScanRecord r;
    r.seq = seq;
    r.file = anascan::acquisition::scan_file_name(seq);
    r.device_id = "sim:tof/small-block";
    r.state = state;
    r.group = group;
    if (with_pose) r.pose = Pose::Identity();
    return r;
}

TEST(SessionView, RowTakesTheRegistrarsFiguresInMillimetresAndPercent) {
    ScanRecord r = record(3, ScanState::kRegistered, 0);
    r.quality_json = R"({"method": "motion-prior", "rms_m": 0.00042, "overlap_fraction": 0.61})";
    const gui::ScanRow row = gui::scan_row(r);
    EXPECT_EQ(row.seq, 3);
    EXPECT_EQ(row.state, gui::ScanRowState::kRegistered);
    EXPECT_EQ(row.group, 0);
    ASSERT_TRUE(row.rms_mm && row.overlap_percent);
    EXPECT_NEAR(*row.rms_mm, 0.42, 1e-9);
    EXPECT_NEAR(*row.overlap_percent, 61.0, 1e-9);
}

TEST(SessionView, ExcludedFailedAndDamagedRowsSayWhy) {
    ScanRecord excluded = record(1, ScanState::kRegistered, 0);
    excluded.excluded = true;
    EXPECT_EQ(gui::scan_row(excluded).state, gui::ScanRowState::kExcluded);

    ScanRecord failed = record(2, ScanState::kFailed, -1, false);
    failed.quality_json = R"({"reason": "no overlap with any scan"})";
    EXPECT_EQ(gui::scan_row(failed).message, "no overlap with any scan");
    failed.quality_json = "not json";
    EXPECT_FALSE(gui::scan_row(failed).rms_mm.has_value());

    ScanRecord damaged = record(4, ScanState::kFailed, -1, false);
    damaged.file_problem = "truncated";
    EXPECT_NE(gui::scan_row(damaged).message.find("scan_000004.ply"), std::string::npos);
}

TEST(SessionView, CoverageJsonGivesTheFractionAndTheHoles) {
    const auto c = gui::parse_coverage_json(
        R"({"status": "ok", "fraction": 0.83125, "holes": [
            {"area_m2": 0.0125, "sample_count": 40, "centre_m": [0.1, 0.2, 0.0],
             "normal": [0.0, 0.0, -1.0]},
            {"area_m2": 0.002, "centre_m": [1, 2], "normal": [0, 0, 1]}]})");
    ASSERT_TRUE(c.fraction);
    EXPECT_DOUBLE_EQ(*c.fraction, 0.83125);
    ASSERT_EQ(c.holes.size(), 1u);  // the second hole's centre is malformed
    EXPECT_DOUBLE_EQ(c.holes[0].area_m2, 0.0125);
    EXPECT_DOUBLE_EQ(c.holes[0].centre_m.y(), 0.2);
    EXPECT_DOUBLE_EQ(c.holes[0].normal.z(), -1.0);
    EXPECT_FALSE(gui::parse_coverage_json("{broken").fraction.has_value());
}

TEST(SessionView, TheViewDrawsTheLargestGroupsRegisteredScans) {
    std::vector<ScanRecord> scans{
        record(1, ScanState::kRegistered, 1), record(2, ScanState::kRegistered, 0),
        record(3, ScanState::kRegistered, 0), record(4, ScanState::kFailed, -1, false),
        record(5, ScanState::kQueued, -1, false)};
    EXPECT_EQ(gui::model_group(scans), 0);
    EXPECT_FALSE(gui::drawn_in_view(scans[0], 0));
    EXPECT_TRUE(gui::drawn_in_view(scans[1], 0));
    EXPECT_FALSE(gui::drawn_in_view(scans[3], 0));
    scans[1].excluded = scans[2].excluded = true;
    EXPECT_EQ(gui::model_group(scans), 1);
    EXPECT_FALSE(gui::drawn_in_view(scans[1], 0));
    EXPECT_EQ(gui::model_group({}), -1);
}

TEST(SessionView, CheckSummaryIsEmptyWhenCleanAndNamesTheFileOtherwise) {
    anascan::acquisition::SessionCheckReport report;
    report.dir = "/data/block7";
    report.scans_checked = report.scans_ok = 5;
    EXPECT_TRUE(gui::check_summary(report).empty());
    report.scans_ok = 4;
    report.issues.push_back({.kind = anascan::acquisition::CheckIssueKind::kDamagedFile,
                             .seq = 3,
                             .file = "/data/block7/scans/scan_000003.ply",
                             .problem = "truncated after 812 bytes"});
    const std::string text = gui::check_summary(report);
    EXPECT_NE(text.find("scan_000003.ply: truncated"), std::string::npos) << text;
    EXPECT_NE(text.find("--repair"), std::string::npos) << text;
}

TEST(SessionView, CaptureProblemsSayWhatHappenedAndWhatToDo) {
    using anascan::Error;
    using anascan::ErrorCode;
    const gui::CaptureProblem away = gui::capture_problem(
        Error{ErrorCode::kDisconnected, "sim:tof/small-block: device went away"});
    EXPECT_NE(away.line().find("sim:tof/small-block"), std::string::npos) << away.line();
    EXPECT_NE(away.headline.find("unplugged"), std::string::npos) << away.headline;
    EXPECT_NE(away.what_to_try.find("cable"), std::string::npos) << away.what_to_try;

    // acquisition's text for EFBIG / ENOSPC ends with its advice "The disk is full: ...".
    const gui::CaptureProblem full = gui::capture_problem(
        Error{ErrorCode::kIo,
              "cannot save scan 1 in session /data/s: File too large. Nothing was recorded for "
              "this scan; scans saved before are safe. The disk is full: free space and retry."});
    EXPECT_EQ(full.headline, "DISK FULL: the scan was NOT saved");
    EXPECT_NE(full.line().find("/data/s"), std::string::npos) << "names the session";
    EXPECT_NE(full.what_to_try.find("Free space"), std::string::npos) << full.what_to_try;

    const gui::CaptureProblem other =
        gui::capture_problem(Error{ErrorCode::kInvalidArgument, "bad exposure 0 ms"});
    EXPECT_NE(other.line().find("bad exposure 0 ms"), std::string::npos);
    EXPECT_FALSE(other.what_to_try.empty());
    EXPECT_EQ(other.line().find("DISK FULL"), std::string::npos);
}

TEST(ScanPreview, ShowsWhatTheSensorSawNearBrightFarDark) {
    // A wall 2 m in front of the sensor (camera frame: z forward) with a box 0.5 m nearer
    // on its left half; the sensor sits at (0, 0, -1) of the scan frame.
    anascan::Scan scan;
    scan.meta.sequence = 7;
    scan.meta.sensor_origin_scan_m = Eigen::Vector3d(0.0, 0.0, -1.0);
    for (int i = 0; i <= 100; ++i) {
        for (int j = 0; j <= 50; ++j) {
            const float x = -1.0f + 0.02f * static_cast<float>(i);
            const float y = -0.5f + 0.02f * static_cast<float>(j);
            scan.cloud.positions.emplace_back(x, y, x < 0.0f ? 0.5f : 1.0f);
        }
    }
    const gui::ScanPreview preview = gui::make_scan_preview(scan, 80);
    EXPECT_EQ(preview.seq, 7);
    EXPECT_EQ(preview.points, scan.cloud.size());
    ASSERT_EQ(preview.width_px, 80);
    EXPECT_GT(preview.height_px, 20) << "a 2:1 field of view";
    EXPECT_LT(preview.height_px, 60);
    ASSERT_EQ(preview.rgb.size(), 3u * 80u * static_cast<std::size_t>(preview.height_px));
    auto grey = [&](int x, int y) {
        return preview.rgb[3 * (static_cast<std::size_t>(y) * 80 + static_cast<std::size_t>(x))];
    };
    const int mid = preview.height_px / 2;
    EXPECT_GT(grey(15, mid), grey(65, mid)) << "the nearer box (left) is brighter";
    EXPECT_TRUE(gui::make_scan_preview(anascan::Scan{}).rgb.empty());
}

}  // namespace

namespace {

TEST(SessionView, AScanThatJoinedNothingIsUnjoinedNotOk) {
    std::vector<ScanRecord> records{record(1, ScanState::kRegistered, 0),
                                    record(2, ScanState::kRegistered, 0),
                                    record(3, ScanState::kRegistered, 1)};
    records[0].quality_json = R"({"method": "first", "rms_m": 0.0, "overlap_fraction": 0.0})";
    records[1].quality_json =
        R"({"method": "motion-prior", "rms_m": 0.0004, "overlap_fraction": 0.6})";
    records[2].quality_json = R"({"method": "new-group", "rms_m": 0.0, "overlap_fraction": 0.0})";
    std::vector<gui::ScanRow> rows;
    for (const ScanRecord& r : records) rows.push_back(gui::scan_row(r));
    gui::mark_unjoined(rows);
    EXPECT_EQ(rows[0].state, gui::ScanRowState::kRegistered);  // scan 2 joined it
    EXPECT_EQ(rows[1].state, gui::ScanRowState::kRegistered);
    EXPECT_EQ(rows[2].state, gui::ScanRowState::kUnjoined);
    EXPECT_STREQ(gui::to_string(rows[2].state), "unjoined");
    // Placed without a match: no RMS 0.00 and no overlap 0 that read as measured.
    EXPECT_FALSE(rows[2].rms_mm.has_value());
    EXPECT_FALSE(rows[2].overlap_percent.has_value());
    EXPECT_FALSE(rows[0].rms_mm.has_value());
    ASSERT_TRUE(rows[1].rms_mm.has_value());
    // Its own colour, unlike a registered scan's.
    EXPECT_FALSE(gui::quality_color(rows[2]) == gui::quality_color(rows[1]));
    // Excluding scan 2 leaves scan 1 alone too.
    records[1].excluded = true;
    rows.clear();
    for (const ScanRecord& r : records) rows.push_back(gui::scan_row(r));
    gui::mark_unjoined(rows);
    EXPECT_EQ(rows[0].state, gui::ScanRowState::kUnjoined);
}

}  // namespace

namespace {

// One codec: the field app reads the coverage JSON with processing's reader, which gives
// back what processing's writer wrote.
TEST(SessionView, CoverageJsonReadsBackWhatTheWriterWrote) {
    anascan::CoverageReport report;
    report.status = anascan::CoverageStatus::kNoStone;
    report.fraction = 0.43712;
    report.surface_area_m2 = 0.528311;
    report.covered_area_m2 = 0.230944;
    report.sparse_area_m2 = 0.0123;
    report.message = R"(too few "stone" points\ here)";
    for (int i = 0; i < 3; ++i)
        report.holes.push_back({.area_m2 = 0.01 / (i + 1),
                                .centre_m = Eigen::Vector3d(0.1 * i, -0.2, 0.35),
                                .normal = Eigen::Vector3d(0.0, 0.6, 0.8),
                                .sample_count = std::size_t(40 - i)});
    const std::string json = anascan::coverage_to_json(report, 2);
    const auto read = anascan::coverage_from_json(json);
    ASSERT_TRUE(read.has_value()) << read.error().message;
    EXPECT_EQ(read->status, anascan::CoverageStatus::kNoStone);
    EXPECT_NEAR(*read->fraction, report.fraction, 1e-5);
    EXPECT_NEAR(*read->surface_area_m2, report.surface_area_m2, 1e-6);
    EXPECT_NEAR(*read->covered_area_m2, report.covered_area_m2, 1e-6);
    EXPECT_NEAR(*read->sparse_area_m2, report.sparse_area_m2, 1e-6);
    EXPECT_EQ(read->hole_count, 3u) << "all holes are counted";
    ASSERT_EQ(read->holes.size(), 2u) << "at most max_holes are listed";
    EXPECT_NEAR(read->holes[1].area_m2, 0.005, 1e-6);
    EXPECT_NEAR(read->holes[1].centre_m.x(), 0.1, 1e-5);
    EXPECT_NEAR(read->holes[1].normal.z(), 0.8, 1e-4);
    EXPECT_EQ(read->holes[1].sample_count, 39u);
    EXPECT_EQ(read->message, report.message);
    // The field app's view of the same text.
    const gui::StoredCoverage shown = gui::parse_coverage_json(json);
    ASSERT_TRUE(shown.fraction);
    EXPECT_DOUBLE_EQ(*shown.fraction, *read->fraction);
    EXPECT_EQ(shown.holes.size(), 2u);
    const auto broken = anascan::coverage_from_json(R"({"fraction": )");
    ASSERT_FALSE(broken.has_value());
    EXPECT_EQ(broken.error().code, anascan::ErrorCode::kFormat);
}

}  // namespace
