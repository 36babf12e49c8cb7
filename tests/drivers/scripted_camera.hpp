#pragma once
// An in-process camera for tests of what sits on top of Camera (recording, stream runner,
// depth scanner): frames of mock_pixel values, an optional unplug after N frames.

#include <memory>

#include "anascan/drivers/camera.hpp"

namespace anascan::drivers::test {

struct ScriptedCameraConfig {
    int width = 16;
    int height = 12;
    PixelFormat format = PixelFormat::kZ16;
    int unplug_after_frames = -1;  ///< -1: never.
    bool silent = false;           ///< Every next_frame waits its timeout, then kTimeout.
    std::string calibration_json = R"({"fx_px":20.0})";
};

std::unique_ptr<Camera> make_scripted_camera(const ScriptedCameraConfig& config = {});

}  // namespace anascan::drivers::test
