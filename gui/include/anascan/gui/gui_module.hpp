#pragma once
/// \file
/// The gui module (anascan-field). It talks only to acquisition.

#include <string_view>

namespace anascan::gui {

/// Name of the field application this module builds.
std::string_view field_app_name();

}  // namespace anascan::gui
