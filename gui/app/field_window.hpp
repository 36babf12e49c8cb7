#pragma once
/// \file
/// The app's window: GLFW window with an OpenGL 3.3 core context and the ImGui context with
/// its GLFW and OpenGL3 backends. One RAII owner: construction order init → use, shutdown
/// in reverse (as Dear ImGui's example). Use on the main thread only (GLFW's rule).

#include <memory>
#include <optional>
#include <string>

#include "anascan/processing/core/expected.hpp"

struct GLFWwindow;

namespace anascan::field {

struct WindowConfig {
    /// Window size; absent: the screen's (the primary monitor's video mode; Xvfb's -screen).
    std::optional<int> width_px, height_px;
    bool visible = true;  ///< Hidden windows still render (used for screenshots).
    bool vsync = false;   ///< On when interactive; off when measuring frame times (--frames).
    float font_scale = 1.5f;
};

class FieldWindow {
public:
    /// Opens the window; the error says what failed (no display, no GL 3.3).
    static Expected<std::unique_ptr<FieldWindow>> open(const WindowConfig& config);
    ~FieldWindow();
    FieldWindow(const FieldWindow&) = delete;
    FieldWindow& operator=(const FieldWindow&) = delete;

    bool should_close() const;
    /// Takes the pending events, or with idle_wait_s > 0 waits up to that long for one (an
    /// idle window leaves the CPU to capture and registration).
    void wait_events(double idle_wait_s);
    /// Starts an ImGui frame (after wait_events).
    void begin_frame();
    /// Renders ImGui's draw data over the scene (call after drawing the scene).
    void render_ui();
    void swap();
    void framebuffer_size(int& width_px, int& height_px) const;
    /// True when a scaled TrueType font was loaded (else ImGui's default font is scaled).
    bool font_scaled() const { return font_scaled_; }
    /// The GL renderer string ("llvmpipe (LLVM 15.0.6, 256 bits)").
    std::string renderer_name() const;

private:
    explicit FieldWindow(GLFWwindow* window) : window_(window) {}
    void use_nearest_font_filter();
    GLFWwindow* window_ = nullptr;
    bool imgui_glfw_ = false;
    bool imgui_gl_ = false;
    bool font_scaled_ = false;
    unsigned nearest_font_texture_ = 0;  ///< The font texture last set to GL_NEAREST.
};

}  // namespace anascan::field
