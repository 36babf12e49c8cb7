#pragma once
/// \file
/// The look of the field app: a dark theme and a high-contrast one for a tent in bright
/// light, both with large type for gloved, tired operators.

namespace anascan::gui {

struct ThemeConfig {
    bool high_contrast = false;  ///< Black on white-bright widgets, yellow accents.
    float font_scale = 1.5f;     ///< Multiplies every size (fonts, padding, rounding).
};

/// Sets the current ImGui context's style colours and sizes (from a fresh default style,
/// so switching back and forth does not accumulate scaling) and io.FontGlobalScale when no
/// scaled font was loaded. Needs a current ImGui context.
void apply_theme(const ThemeConfig& config, bool font_already_scaled);

/// Loads DejaVu Sans at 15 px × font_scale (the first font: the text) and 1.3 times that
/// (the second: the banner's headline) into the current context's font atlas when the font
/// file exists (Debian fonts-dejavu-core); returns false (ImGui's default font stays)
/// otherwise. Call before the atlas is built.
bool load_scaled_font(float font_scale);

}  // namespace anascan::gui
