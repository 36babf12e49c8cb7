// The operator's device calls of a CaptureSession: the device's settings as a form (units,
// ranges), applying them (validated by the device, kept, recorded in the session and in
// the next scans) and the camera preview of the structured-light scanner.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "anascan/acquisition/capture/capture_session.hpp"
#include "sim_devices_fixture.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

class DeviceControlTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(::testing::TempDir()) / ("device-control-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        auto store = SessionStore::open(dir_, SessionOpenMode::kCreateOrOpen);
        ASSERT_TRUE(store) << store.error().message;
        auto session = CaptureSession::start(std::move(*store),
                                             {.register_live = false, .coverage_live = false},
                                             [](const SessionEvent&) {});
        ASSERT_TRUE(session) << session.error().message;
        session_ = std::move(*session);
    }
    void TearDown() override {
        session_.reset();
        fs::remove_all(dir_);
    }

    void attach_tof() {
        ASSERT_TRUE(session_->attach_scanner(
            "sim:tof/small-block", []() -> Expected<std::unique_ptr<drivers::Scanner>> {
                return std::unique_ptr<drivers::Scanner>(
                    sim::SimTofScanner::open(sim::test::small_tof_config()));
            }));
    }
    void attach_sl() {
        ASSERT_TRUE(session_->attach_scanner(
            "sim:structured-light/small-block",
            []() -> Expected<std::unique_ptr<drivers::Scanner>> {
                return std::unique_ptr<drivers::Scanner>(
                    sim::SimStructuredLightScanner::open(sim::test::small_sl_config()));
            }));
    }

    fs::path dir_;
    std::unique_ptr<CaptureSession> session_;
};

const DeviceSetting* find(const DeviceSettingsForm& form, const std::string& key) {
    const auto it = std::find_if(form.settings.begin(), form.settings.end(),
                                 [&](const DeviceSetting& s) { return s.key == key; });
    return it == form.settings.end() ? nullptr : &*it;
}

TEST_F(DeviceControlTest, TofSettingsComeWithUnitsAndRanges) {
    attach_tof();
    auto form = session_->device_settings().get();
    ASSERT_TRUE(form) << form.error().message;
    EXPECT_EQ(form->device, "sim:tof/small-block");
    const DeviceSetting* step = find(*form, "angular_step_deg");
    ASSERT_NE(step, nullptr);
    EXPECT_EQ(step->unit, "°");
    EXPECT_EQ(step->kind, DeviceSettingKind::kNumber);
    EXPECT_LT(step->min, step->max);
    EXPECT_DOUBLE_EQ(step->value, 2.0);  // the fixture's setting, as the device reports it
    const DeviceSetting* far = find(*form, "max_range_m");
    ASSERT_NE(far, nullptr);
    EXPECT_EQ(far->unit, "m");
    EXPECT_EQ(find(*form, "exposure_us"), nullptr) << "the ToF scanner has no exposure";
}

TEST_F(DeviceControlTest, AppliedSettingsAreKeptRecordedAndCarriedByTheNextScan) {
    attach_tof();
    auto form = session_->device_settings().get();
    ASSERT_TRUE(form);
    DeviceSettingsForm edited = *form;
    auto& step = *std::find_if(edited.settings.begin(), edited.settings.end(),
                               [](const DeviceSetting& s) { return s.key == "angular_step_deg"; });
    step.value = 3.0;
    auto now = session_->apply_device_settings(edited).get();
    ASSERT_TRUE(now) << now.error().message;
    EXPECT_DOUBLE_EQ(find(*now, "angular_step_deg")->value, 3.0);
    EXPECT_DOUBLE_EQ(find(*session_->device_settings().get(), "angular_step_deg")->value, 3.0);

    auto events = session_->store().events();
    ASSERT_TRUE(events);
    const auto recorded = std::find_if(events->begin(), events->end(), [](const EventRecord& e) {
        return e.kind == "device-settings";
    });
    ASSERT_NE(recorded, events->end()) << "the applied settings are a session event";
    EXPECT_EQ(recorded->device, "sim:tof/small-block");
    EXPECT_DOUBLE_EQ(nlohmann::json::parse(recorded->message).at("angular_step_deg").get<double>(),
                     3.0)
        << recorded->message;

    auto seq = session_->capture({}).get();
    ASSERT_TRUE(seq) << seq.error().message;
    auto record = session_->store().scan(*seq);
    ASSERT_TRUE(record);
    EXPECT_DOUBLE_EQ(
        nlohmann::json::parse(record->settings_json).at("angular_step_deg").get<double>(), 3.0)
        << record->settings_json;
}

TEST_F(DeviceControlTest, AnInvalidValueIsRefusedNamingTheSettingAndChangesNothing) {
    attach_tof();
    auto form = session_->device_settings().get();
    ASSERT_TRUE(form);
    DeviceSettingsForm edited = *form;
    for (DeviceSetting& s : edited.settings)
        if (s.key == "angular_step_deg") s.value = s.max * 10.0;
    auto refused = session_->apply_device_settings(edited).get();
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(refused.error().message.find("sim:tof/small-block"), std::string::npos);
    EXPECT_NE(refused.error().message.find("angular_step_deg"), std::string::npos)
        << refused.error().message;
    EXPECT_EQ(*session_->device_settings().get(), *form) << "nothing changed";

    DeviceSettingsForm unknown = *form;
    unknown.settings.push_back({.key = "laser_power", .value = 1.0});
    auto no_such = session_->apply_device_settings(unknown).get();
    ASSERT_FALSE(no_such);
    EXPECT_NE(no_such.error().message.find("laser_power"), std::string::npos);
}

TEST_F(DeviceControlTest, StructuredLightPreviewHasBothCamerasDownscaled) {
    attach_sl();
    auto preview = session_->preview_cameras(80).get();
    ASSERT_TRUE(preview) << preview.error().message;
    ASSERT_EQ(preview->images.size(), 2u);
    for (const CameraImage& image : preview->images) {
        EXPECT_EQ(image.width_px, 80) << image.camera;  // 160 px cameras, halved
        EXPECT_EQ(image.height_px, 60) << image.camera;
        ASSERT_EQ(image.grey.size(), 80u * 60u);
        const auto [lo, hi] = std::minmax_element(image.grey.begin(), image.grey.end());
        EXPECT_GT(*hi - *lo, 40) << image.camera << ": the lit block stands out of the dark";
    }
    EXPECT_NE(preview->images[0].grey, preview->images[1].grey) << "two viewpoints";
    // A capture after the preview still works (the streams were stopped).
    auto seq = session_->capture({}).get();
    EXPECT_TRUE(seq) << seq.error().message;
}

TEST_F(DeviceControlTest, ScannerWithoutCamerasHasAnEmptyPreview) {
    attach_tof();
    auto preview = session_->preview_cameras(80).get();
    ASSERT_TRUE(preview) << preview.error().message;
    EXPECT_TRUE(preview->images.empty());
}

TEST_F(DeviceControlTest, WithoutAScannerTheCallsSaySo) {
    auto form = session_->device_settings().get();
    ASSERT_FALSE(form);
    EXPECT_NE(form.error().message.find("no scanner attached"), std::string::npos);
}

}  // namespace
}  // namespace anascan::acquisition
