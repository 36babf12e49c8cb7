#pragma once
// What the X server shows (kept apart: X11's macros clash with GoogleTest's names).

#include "anascan/drivers/projector_output.hpp"

namespace anascan::drivers::test {

/// The red channel of the top-left w x h pixels of the default screen; empty without X.
Pattern screen_from_x_server(int w, int h);

}  // namespace anascan::drivers::test
