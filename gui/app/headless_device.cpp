#include "headless_device.hpp"

#include <algorithm>
#include <charconv>

namespace anascan::field {
namespace {

Expected<double> setting_value(const acquisition::DeviceSetting& s, const std::string& text,
                               const std::string& device) {
    if (s.kind == acquisition::DeviceSettingKind::kChoice) {
        const auto it = std::find(s.choices.begin(), s.choices.end(), text);
        if (it == s.choices.end())
            return fail(ErrorCode::kInvalidArgument,
                        device + ": " + s.key + " has no choice \"" + text + "\"");
        return static_cast<double>(it - s.choices.begin());
    }
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
        return fail(ErrorCode::kInvalidArgument,
                    device + ": " + s.key + " = \"" + text + "\" is not a number");
    return value;
}

}  // namespace

Expected<gui::UiActions> setting_actions(const gui::DeviceSettingsState& settings,
                                         const std::vector<std::string>& key_values) {
    const auto& fields = settings.edited.settings;
    const std::string& device = settings.edited.device;
    gui::UiActions actions;
    for (const std::string& kv : key_values) {
        const auto eq = kv.find('=');
        const std::string key = kv.substr(0, eq);
        const auto it =
            std::find_if(fields.begin(), fields.end(),
                         [&](const acquisition::DeviceSetting& s) { return s.key == key; });
        if (eq == std::string::npos || it == fields.end())
            return fail(ErrorCode::kInvalidArgument,
                        (device.empty() ? std::string("the device") : device) +
                            " has no setting \"" + key + "\" (give KEY=VALUE)");
        auto value = setting_value(*it, kv.substr(eq + 1), device);
        if (!value) return fail(value.error());
        actions.push_back({.kind = gui::UiActionKind::kEditSetting,
                           .setting_index = static_cast<int>(it - fields.begin()),
                           .value = *value});
    }
    actions.push_back({.kind = gui::UiActionKind::kApplySettings});
    return actions;
}

}  // namespace anascan::field
