#include "x_screen.hpp"

#include <X11/Xlib.h>
#include <X11/Xutil.h>

namespace anascan::drivers::test {

Pattern screen_from_x_server(int w, int h) {
    Display* display = XOpenDisplay(nullptr);
    if (display == nullptr) return {};
    Pattern p{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h)};
    XImage* image = XGetImage(display, DefaultRootWindow(display), 0, 0, static_cast<unsigned>(w),
                              static_cast<unsigned>(h), AllPlanes, ZPixmap);
    for (int r = 0; image != nullptr && r < h; ++r)
        for (int c = 0; c < w; ++c)
            p.grey[static_cast<std::size_t>(r) * w + c] =
                static_cast<std::uint8_t>(XGetPixel(image, c, r) >> 16);
    if (image != nullptr) XDestroyImage(image);
    XCloseDisplay(display);
    return p;
}

}  // namespace anascan::drivers::test
