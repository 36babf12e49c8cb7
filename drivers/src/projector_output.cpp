#define GLFW_INCLUDE_NONE
#include "anascan/drivers/projector_output.hpp"

#include <GL/gl.h>
#include <GLFW/glfw3.h>

#include <thread>

namespace anascan::drivers {
namespace {

struct WindowDeleter {
    void operator()(GLFWwindow* w) const {
        glfwDestroyWindow(w);
        glfwTerminate();  // the window owns the one GLFW initialisation it needed
    }
};
using WindowPtr = std::unique_ptr<GLFWwindow, WindowDeleter>;

class GlfwProjector final : public ProjectorOutput {
public:
    GlfwProjector(WindowPtr window, std::string name)
        : window_(std::move(window)), name_(std::move(name)) {
        glfwGetFramebufferSize(window_.get(), &width_, &height_);
    }
    std::string name() const override { return name_; }
    int width_px() const override { return width_; }
    int height_px() const override { return height_; }
    Expected<void> load(std::span<const Pattern> patterns) override;
    Expected<std::chrono::nanoseconds> show(std::size_t index) override;
    Pattern read_back() const override { return last_; }

private:
    void draw(const Pattern& p);
    void read_frame_buffer();

    WindowPtr window_;
    std::string name_;
    int width_ = 0;
    int height_ = 0;
    std::vector<Pattern> bottom_up_;  ///< The loaded patterns, rows in OpenGL's order.
    std::chrono::milliseconds settle_{0};
    bool keep_read_back_ = false;
    Pattern last_;
    friend Expected<std::unique_ptr<ProjectorOutput>> ProjectorOutput::open(const ProjectorConfig&);
};

// Row 0 of a pattern is the top of the screen; OpenGL draws pixel rows bottom-up.
Pattern flipped(const Pattern& p) {
    Pattern out{p.width, p.height, std::vector<std::uint8_t>(p.grey.size())};
    for (int r = 0; r < p.height; ++r)
        std::copy_n(p.grey.begin() + static_cast<std::ptrdiff_t>(p.height - 1 - r) * p.width,
                    p.width, out.grey.begin() + static_cast<std::ptrdiff_t>(r) * p.width);
    return out;
}

// `p` is bottom-up (flipped()).
void GlfwProjector::draw(const Pattern& p) {
    glfwMakeContextCurrent(window_.get());
    glViewport(0, 0, width_, height_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // A raster position on the window's corner may be clipped; set it at the centre, then
    // move it to the corner with a null bitmap (the classic OpenGL idiom).
    glRasterPos2f(0.0f, 0.0f);
    glBitmap(0, 0, 0.0f, 0.0f, -0.5f * static_cast<float>(width_),
             -0.5f * static_cast<float>(height_), nullptr);
    glDrawPixels(p.width, p.height, GL_LUMINANCE, GL_UNSIGNED_BYTE, p.grey.data());
    glFinish();
    if (keep_read_back_) read_frame_buffer();
    glfwSwapBuffers(window_.get());
    glFinish();
    glfwPollEvents();
}

Expected<void> GlfwProjector::load(std::span<const Pattern> patterns) {
    if (auto ok = check_patterns(patterns, width_, height_, name_); !ok) return ok;
    bottom_up_.clear();
    for (const Pattern& p : patterns) bottom_up_.push_back(flipped(p));
    return {};
}

Expected<std::chrono::nanoseconds> GlfwProjector::show(std::size_t index) {
    if (auto ok = check_pattern_index(index, bottom_up_.size(), name_); !ok)
        return fail(ok.error());
    if (glfwWindowShouldClose(window_.get()))
        return fail(ErrorCode::kDisconnected, name_ + ": the window was closed");
    draw(bottom_up_[index]);
    if (settle_.count() > 0) std::this_thread::sleep_for(settle_);
    return steady_now();
}

void GlfwProjector::read_frame_buffer() {
    last_ = Pattern{width_, height_,
                    std::vector<std::uint8_t>(static_cast<std::size_t>(width_) * height_)};
    std::vector<std::uint8_t> bottom_up(last_.grey.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width_, height_, GL_RED, GL_UNSIGNED_BYTE, bottom_up.data());
    for (int r = 0; r < height_; ++r)
        std::copy_n(bottom_up.begin() + static_cast<std::ptrdiff_t>(height_ - 1 - r) * width_,
                    width_, last_.grey.begin() + static_cast<std::ptrdiff_t>(r) * width_);
}

}  // namespace

Expected<void> check_patterns(std::span<const Pattern> patterns, int width_px, int height_px,
                              const std::string& output) {
    for (std::size_t i = 0; i < patterns.size(); ++i) {
        const Pattern& p = patterns[i];
        if (p.width != width_px || p.height != height_px ||
            p.grey.size() != static_cast<std::size_t>(p.width) * p.height) {
            return fail(ErrorCode::kInvalidArgument,
                        output + ": pattern " + std::to_string(i) + " is " +
                            std::to_string(p.width) + " x " + std::to_string(p.height) +
                            " px, the output " + std::to_string(width_px) + " x " +
                            std::to_string(height_px) + " px");
        }
    }
    return {};
}

Expected<void> check_pattern_index(std::size_t index, std::size_t loaded,
                                   const std::string& output) {
    if (index < loaded) return {};
    return fail(ErrorCode::kInvalidArgument, output + ": pattern " + std::to_string(index) +
                                                 " of " + std::to_string(loaded) + " loaded");
}

Expected<void> ProjectorOutput::show_sequence(std::span<const Pattern> patterns,
                                              const std::function<bool(std::size_t)>& on_shown,
                                              std::stop_token stop) {
    if (auto ok = load(patterns); !ok) return ok;
    for (std::size_t i = 0; i < patterns.size(); ++i) {
        if (stop.stop_requested())
            return fail(ErrorCode::kCancelled, name() + ": sequence stopped");
        if (auto shown = show(i); !shown) return fail(shown.error());
        if (on_shown && !on_shown(i)) {
            return fail(ErrorCode::kCancelled,
                        name() + ": sequence stopped after pattern " + std::to_string(i));
        }
    }
    return {};
}

std::vector<MonitorInfo> ProjectorOutput::monitors() {
    std::vector<MonitorInfo> out;
    if (!glfwInit()) return out;
    int count = 0;
    GLFWmonitor** list = glfwGetMonitors(&count);
    for (int i = 0; i < count; ++i) {
        const GLFWvidmode* mode = glfwGetVideoMode(list[i]);
        out.push_back({glfwGetMonitorName(list[i]), mode ? mode->width : 0, mode ? mode->height : 0,
                       mode ? static_cast<double>(mode->refreshRate) : 0.0});
    }
    glfwTerminate();
    return out;
}

Expected<std::unique_ptr<ProjectorOutput>> ProjectorOutput::open(const ProjectorConfig& config) {
    if (!glfwInit())
        return fail(ErrorCode::kUnsupported, "projector: no display (GLFW cannot start)");
    int count = 0;
    GLFWmonitor** list = glfwGetMonitors(&count);
    const int index = config.monitor_index < 0 ? count - 1 : config.monitor_index;
    if (config.fullscreen && (index < 0 || index >= count)) {
        glfwTerminate();
        return fail(ErrorCode::kInvalidArgument,
                    "projector: monitor " + std::to_string(config.monitor_index) +
                        " does not exist (" + std::to_string(count) + " connected)");
    }
    GLFWmonitor* monitor = config.fullscreen ? list[index] : nullptr;
    const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
    glfwWindowHint(GLFW_AUTO_ICONIFY, GLFW_FALSE);  // stay up when the operator clicks elsewhere
    glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
    GLFWwindow* raw = glfwCreateWindow(mode ? mode->width : config.window_width_px,
                                       mode ? mode->height : config.window_height_px,
                                       "anascan projector", monitor, nullptr);
    if (raw == nullptr) {
        glfwTerminate();
        return fail(ErrorCode::kUnsupported, "projector: cannot create an OpenGL window");
    }
    WindowPtr window(raw);
    glfwMakeContextCurrent(raw);
    glfwSwapInterval(1);  // swap on vertical blank: a pattern is whole on screen
    const std::string name = monitor ? "projector (monitor " + std::to_string(index) + ", " +
                                           glfwGetMonitorName(monitor) + ")"
                                     : std::string("projector (window)");
    auto projector = std::make_unique<GlfwProjector>(std::move(window), name);
    projector->settle_ = config.settle;
    projector->keep_read_back_ = config.keep_read_back;
    return std::unique_ptr<ProjectorOutput>(std::move(projector));
}

}  // namespace anascan::drivers
