#include <gtest/gtest.h>

#include <string>

#include "anascan/drivers/device_uri.hpp"

namespace anascan::drivers {
namespace {

void expect_parses(const std::string& text, const std::string& scheme, const std::string& target) {
    const auto uri = parse_device_uri(text);
    ASSERT_TRUE(uri) << text << ": " << uri.error().message;
    EXPECT_EQ(uri->scheme, scheme) << text;
    EXPECT_EQ(uri->target, target) << text;
    EXPECT_EQ(to_string(*uri), text);
}

void expect_rejects(const std::string& text, const std::string& message_part) {
    const auto uri = parse_device_uri(text);
    ASSERT_FALSE(uri) << text << " parsed as " << to_string(*uri);
    EXPECT_EQ(uri.error().code, ErrorCode::kInvalidArgument) << text;
    EXPECT_NE(uri.error().message.find(message_part), std::string::npos)
        << text << ": " << uri.error().message;
}

TEST(DeviceUri, ParsesSimulatedDevices) {
    expect_parses("sim:structured-light", "sim", "structured-light");
    expect_parses("sim:tof", "sim", "tof");
}

TEST(DeviceUri, ParsesV4l2AndPtxPaths) {
    expect_parses("v4l2:/dev/video2", "v4l2", "/dev/video2");
    expect_parses("ptx:/data/station exports/a:b", "ptx", "/data/station exports/a:b");
}

TEST(DeviceUri, ParsesUsbIds) {
    expect_parses("usb:1d6b:0104", "usb", "1d6b:0104");
    expect_parses("usb:8086:0B3A", "usb", "8086:0B3A");
}

TEST(DeviceUri, EqualityAndRoundTrip) {
    const auto a = parse_device_uri("sim:tof");
    ASSERT_TRUE(a);
    EXPECT_EQ(*a, (DeviceUri{"sim", "tof"}));
    EXPECT_NE(*a, (DeviceUri{"sim", "structured-light"}));
}

TEST(DeviceUri, RejectsMissingColon) {
    expect_rejects("structured-light", "expected SCHEME:TARGET");
    expect_rejects("", "expected SCHEME:TARGET");
}

TEST(DeviceUri, RejectsEmptySchemeOrTarget) {
    expect_rejects("sim:", "expected SCHEME:TARGET");
    expect_rejects(":tof", "expected SCHEME:TARGET");
}

TEST(DeviceUri, RejectsBadUsbIds) {
    for (const char* text : {"usb:1d6b", "usb:1d6b:", "usb:1d6b:104", "usb:1d6g:0104",
                             "usb:1d6b:01045", "usb::0104", "usb:1d6b:0104:1"}) {
        expect_rejects(text, "usb:VID:PID");
    }
}

TEST(DeviceUri, RejectsUpperCaseOrOddSchemes) {
    expect_rejects("SIM:tof", "must be lower-case");
    expect_rejects("Usb:1d6b:0104", "must be lower-case");
    expect_rejects("v4l-2:/dev/video0", "must be lower-case");
}

TEST(DeviceUri, ErrorsQuoteTheText) { expect_rejects("usb:zzzz:0000", "'usb:zzzz:0000'"); }

}  // namespace
}  // namespace anascan::drivers
