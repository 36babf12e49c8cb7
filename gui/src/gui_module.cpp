#include "anascan/gui/gui_module.hpp"

namespace anascan::gui {

std::string_view field_app_name() { return "anascan-field"; }

}  // namespace anascan::gui
