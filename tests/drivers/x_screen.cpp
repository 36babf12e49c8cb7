#include "x_screen.hpp"

#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <vector>

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

namespace {

/// The windows under `parent` (depth first) whose name is `title`.
void find_titled(Display* display, Window parent, const std::string& title,
                 std::vector<Window>& out) {
    Window root = 0, up = 0;
    Window* children = nullptr;
    unsigned count = 0;
    if (XQueryTree(display, parent, &root, &up, &children, &count) == 0) return;
    for (unsigned i = 0; i < count; ++i) {
        char* name = nullptr;
        if (XFetchName(display, children[i], &name) != 0 && name != nullptr) {
            if (title == name) out.push_back(children[i]);
            XFree(name);
        }
        find_titled(display, children[i], title, out);
    }
    if (children != nullptr) XFree(children);
}

}  // namespace

int close_windows_titled(const std::string& title) {
    Display* display = XOpenDisplay(nullptr);
    if (display == nullptr) return 0;
    std::vector<Window> windows;
    find_titled(display, DefaultRootWindow(display), title, windows);
    const Atom protocols = XInternAtom(display, "WM_PROTOCOLS", False);
    const Atom delete_window = XInternAtom(display, "WM_DELETE_WINDOW", False);
    for (Window w : windows) {
        XEvent e{};
        e.xclient.type = ClientMessage;
        e.xclient.window = w;
        e.xclient.message_type = protocols;
        e.xclient.format = 32;
        e.xclient.data.l[0] = static_cast<long>(delete_window);
        e.xclient.data.l[1] = CurrentTime;
        XSendEvent(display, w, False, NoEventMask, &e);
    }
    XSync(display, False);  // the server has queued the messages to the window's owner
    XCloseDisplay(display);
    return static_cast<int>(windows.size());
}

}  // namespace anascan::drivers::test
