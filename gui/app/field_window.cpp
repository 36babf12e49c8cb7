#define GLFW_INCLUDE_NONE
#include "field_window.hpp"

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <cstdint>
#include <utility>

#include "anascan/gui/theme.hpp"

namespace anascan::field {
namespace {

/// GLFW reports errors through a callback; keep the last one for our error message.
thread_local std::string last_glfw_error;

void on_glfw_error(int code, const char* description) {
    last_glfw_error = "GLFW error " + std::to_string(code) + ": " + description;
}

/// The size asked for, else the screen's (1280 × 800 when GLFW knows no monitor).
std::pair<int, int> window_size(const WindowConfig& config) {
    int width = 1280, height = 800;
    if (GLFWmonitor* monitor = glfwGetPrimaryMonitor()) {
        if (const GLFWvidmode* mode = glfwGetVideoMode(monitor)) {
            width = mode->width;
            height = mode->height;
        }
    }
    return {config.width_px.value_or(width), config.height_px.value_or(height)};
}

}  // namespace

Expected<std::unique_ptr<FieldWindow>> FieldWindow::open(const WindowConfig& config) {
    glfwSetErrorCallback(on_glfw_error);
    if (glfwInit() != GLFW_TRUE) {
        return fail(ErrorCode::kUnsupported, "anascan-field: cannot open the display (" +
                                                 last_glfw_error +
                                                 "); is DISPLAY set? Headless: run under xvfb-run");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_VISIBLE, config.visible ? GLFW_TRUE : GLFW_FALSE);
    const auto [width_px, height_px] = window_size(config);
    GLFWwindow* window = glfwCreateWindow(width_px, height_px, "anascan-field", nullptr, nullptr);
    if (window == nullptr) {
        glfwTerminate();
        return fail(ErrorCode::kUnsupported,
                    "anascan-field: cannot create an OpenGL 3.3 window (" + last_glfw_error + ")");
    }
    std::unique_ptr<FieldWindow> self(new FieldWindow(window));
    glfwMakeContextCurrent(window);
    glfwSwapInterval(config.vsync ? 1 : 0);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the layout comes from PanelLayout, not a file
    self->font_scaled_ = gui::load_scaled_font(config.font_scale);
    self->imgui_glfw_ = ImGui_ImplGlfw_InitForOpenGL(window, true);
    self->imgui_gl_ = ImGui_ImplOpenGL3_Init("#version 330 core");
    if (!self->imgui_glfw_ || !self->imgui_gl_) {
        return fail(ErrorCode::kUnsupported, "anascan-field: ImGui backends failed to start");
    }
    return self;
}

FieldWindow::~FieldWindow() {
    if (imgui_gl_) ImGui_ImplOpenGL3_Shutdown();
    if (imgui_glfw_) ImGui_ImplGlfw_Shutdown();
    if (ImGui::GetCurrentContext() != nullptr) ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
}

bool FieldWindow::should_close() const { return glfwWindowShouldClose(window_) == GLFW_TRUE; }

void FieldWindow::wait_events(double idle_wait_s) {
    if (idle_wait_s > 0.0) {
        glfwWaitEventsTimeout(idle_wait_s);
    } else {
        glfwPollEvents();
    }
}

void FieldWindow::begin_frame() {
    ImGui_ImplOpenGL3_NewFrame();  // creates the font texture at the first frame
    if (font_scaled_) use_nearest_font_filter();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

/// The glyphs are drawn at the size they were rasterised at, on whole pixels (ImGui floors
/// text positions), so nearest filtering draws the same text as linear, and costs llvmpipe
/// far less per pixel (every panel pixel samples the atlas). Once per font texture.
void FieldWindow::use_nearest_font_filter() {
    const auto texture =
        static_cast<GLuint>(reinterpret_cast<std::intptr_t>(ImGui::GetIO().Fonts->TexID));
    if (texture == 0 || texture == nearest_font_texture_) return;
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    nearest_font_texture_ = texture;
}

void FieldWindow::render_ui() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void FieldWindow::swap() { glfwSwapBuffers(window_); }

void FieldWindow::framebuffer_size(int& width_px, int& height_px) const {
    glfwGetFramebufferSize(window_, &width_px, &height_px);
}

std::string FieldWindow::renderer_name() const {
    const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return name != nullptr ? name : "?";
}

}  // namespace anascan::field
