#pragma once
// What the X server shows (kept apart: X11's macros clash with GoogleTest's names).

#include <string>

#include "anascan/drivers/projector_output.hpp"

namespace anascan::drivers::test {

/// The red channel of the top-left w x h pixels of the default screen; empty without X.
Pattern screen_from_x_server(int w, int h);

/// Asks every top-level window titled `title` to close, as a window manager's close button
/// does (a WM_DELETE_WINDOW client message); the number of windows asked.
int close_windows_titled(const std::string& title);

}  // namespace anascan::drivers::test
