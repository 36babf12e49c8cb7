#pragma once
/// \file
/// Headless runs (tests, measurements) operate the device panel as the operator would:
/// `--apply-setting KEY=VALUE` becomes the panel's edit actions followed by "Apply".

#include <string>
#include <vector>

#include "anascan/gui/ui_action.hpp"
#include "anascan/processing/core/expected.hpp"

namespace anascan::field {

/// kEditSetting per "KEY=VALUE" (a number, or a choice's text), then kApplySettings;
/// kInvalidArgument naming the key when the device has no such setting or the value is
/// neither a number nor one of its choices.
Expected<gui::UiActions> setting_actions(const gui::DeviceSettingsState& settings,
                                         const std::vector<std::string>& key_values);

}  // namespace anascan::field
