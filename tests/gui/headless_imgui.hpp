#pragma once
// A headless Dear ImGui context for panel tests: no window, no GL; input is set on ImGuiIO
// before each frame, as a backend would.

#include <imgui.h>
#include <imgui_internal.h>

#include <functional>

class HeadlessImGui {
public:
    explicit HeadlessImGui(float width_px = 1280.0f, float height_px = 800.0f) {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(width_px, height_px);
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);  // builds the font atlas
    }
    ~HeadlessImGui() { ImGui::DestroyContext(); }
    HeadlessImGui(const HeadlessImGui&) = delete;
    HeadlessImGui& operator=(const HeadlessImGui&) = delete;

    /// One frame with the mouse at (x, y), the left button as given, and `key` held (-1: none).
    void frame(const std::function<void()>& draw, ImVec2 mouse = ImVec2(-1.0f, -1.0f),
               bool left_down = false, int key = -1) {
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = mouse;
        io.MouseDown[0] = left_down;
        for (bool& down : io.KeysDown) down = false;
        if (key >= 0) io.KeysDown[key] = true;
        ImGui::NewFrame();
        draw();
        ImGui::Render();
    }

    /// A click (hover, press, release) at (x, y).
    void click(const std::function<void()>& draw, ImVec2 at) {
        frame(draw, at, false);
        frame(draw, at, true);
        frame(draw, at, false);
    }

    /// True when the window of that name was drawn in the last frame.
    static bool window_drawn(const char* name) {
        const ImGuiWindow* window = ImGui::FindWindowByName(name);
        return window != nullptr && window->Active;
    }
};
