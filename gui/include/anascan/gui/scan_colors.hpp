#pragma once
/// \file
/// The colours of the point view: a palette to tell scans apart and a traffic-light scale
/// for registration quality.

#include <cstdint>

#include "anascan/gui/field_view_state.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::gui {

/// A distinct, saturated colour per sequence number (golden-angle hue steps).
Rgb8 scan_palette_color(std::int64_t seq);

/// Registration quality: green (RMS under 0.5 mm), yellow (under 1.5 mm), orange (worse),
/// red (failed), grey (queued or excluded).
Rgb8 quality_color(const ScanRow& row);

}  // namespace anascan::gui
