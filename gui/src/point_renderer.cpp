#include "anascan/gui/point_renderer.hpp"

#include <algorithm>
#include <random>
#include <utility>

#include "anascan/gui/level_of_detail.hpp"
#include "anascan/processing/coverage/coverage.hpp"
#include "hole_marker_geometry.hpp"
#include "shader_program.hpp"

namespace anascan::gui {
namespace {

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "positions upload as packed floats");
static_assert(sizeof(Rgb8) == 3, "colours upload as packed bytes");

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_color;
uniform mat4 u_mvp;
uniform vec3 u_chunk_color;
uniform int u_use_vertex_color;
uniform float u_highlight;
out vec3 v_color;
void main() {
    gl_Position = u_mvp * vec4(a_position, 1.0);
    vec3 c = (u_use_vertex_color == 1) ? a_color : u_chunk_color;
    v_color = mix(c, vec3(1.0), 0.35 * u_highlight);
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 v_color;
out vec4 frag_color;
void main() { frag_color = vec4(v_color, 1.0); }
)";

/// The hole markers: red, as `anascan coverage --ply` colours unobserved samples.
const Rgb8 kHoleColor = coverage_sample_color(SampleState::kUnobserved);
constexpr float kNoColorGrey = 0.7f;

Eigen::Vector3f to_float_rgb(Rgb8 c) { return Eigen::Vector3f(c.r, c.g, c.b) / 255.0f; }

/// A buffer for vertex attribute `index` of the bound vertex array: `components` values of
/// `type` per vertex (bytes are normalised to 0..1). `bytes` of size only (null data):
/// filled later with glBufferSubData.
GLuint upload_attribute(GLuint index, std::span<const std::byte> bytes, GLint components,
                        GLenum type) {
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes.size()), bytes.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, components, type, type == GL_UNSIGNED_BYTE ? GL_TRUE : GL_FALSE, 0,
                          nullptr);
    return buffer;
}

/// A vertex array with a position buffer and an optional colour buffer.
struct VertexArray {
    GLuint vao = 0, positions = 0, colors = 0;
    void upload(std::span<const Eigen::Vector3f> p, std::span<const Rgb8> c) {
        glGenVertexArrays(1, &vao);
        glBindVertexArray(vao);
        positions = upload_attribute(0, std::as_bytes(p), 3, GL_FLOAT);
        if (!c.empty()) colors = upload_attribute(1, std::as_bytes(c), 3, GL_UNSIGNED_BYTE);
        glBindVertexArray(0);
    }
    /// Buffers of n points (with colours or not), filled later by fill().
    void allocate(std::size_t n, bool with_colors) {
        const std::span<const std::byte> p{static_cast<const std::byte*>(nullptr),
                                           n * sizeof(Eigen::Vector3f)};
        const std::span<const std::byte> c{static_cast<const std::byte*>(nullptr),
                                           n * sizeof(Rgb8)};
        glGenVertexArrays(1, &vao);
        glBindVertexArray(vao);
        positions = upload_attribute(0, p, 3, GL_FLOAT);
        if (with_colors) colors = upload_attribute(1, c, 3, GL_UNSIGNED_BYTE);
        glBindVertexArray(0);
    }
    /// Points [begin, end) of the cloud into the buffers.
    void fill(const PointCloud& cloud, std::size_t begin, std::size_t end) const {
        glBindBuffer(GL_ARRAY_BUFFER, positions);
        glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(begin * sizeof(Eigen::Vector3f)),
                        static_cast<GLsizeiptr>((end - begin) * sizeof(Eigen::Vector3f)),
                        cloud.positions.data() + begin);
        if (colors != 0) {
            glBindBuffer(GL_ARRAY_BUFFER, colors);
            glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(begin * sizeof(Rgb8)),
                            static_cast<GLsizeiptr>((end - begin) * sizeof(Rgb8)),
                            cloud.colors.data() + begin);
        }
        glBindBuffer(GL_ARRAY_BUFFER, 0);
    }
    void release() {
        if (colors != 0) glDeleteBuffers(1, &colors);
        if (positions != 0) glDeleteBuffers(1, &positions);
        if (vao != 0) glDeleteVertexArrays(1, &vao);
        vao = positions = colors = 0;
    }
};

}  // namespace

struct PointRenderer::Chunk {
    VertexArray buffers;
    std::size_t count = 0;
    bool has_colors = false;
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
    Eigen::Isometry3d T_world_chunk = Eigen::Isometry3d::Identity();
    BoundingSphere local_sphere;  ///< Relative to origin_m, chunk frame.
    ChunkStyle style;
    std::size_t uploaded = 0;  ///< Points on the GPU; drawn once uploaded == count.
    PointCloud pending;        ///< The cloud until it is all uploaded (then freed).
    std::size_t points_per_step = 0;
    bool complete() const { return uploaded == count; }
    ~Chunk() { buffers.release(); }
};

struct PointRenderer::Gpu {
    GLuint program = 0;
    GLint mvp = -1, chunk_color = -1, use_vertex_color = -1, highlight = -1;
    VertexArray markers;
    std::size_t marker_vertices = 0;
    Eigen::Vector3d markers_origin_m = Eigen::Vector3d::Zero();
    ~Gpu() {
        markers.release();
        if (program != 0) glDeleteProgram(program);
    }
};

PointRenderer::PointRenderer() : gpu_(std::make_unique<Gpu>()) {}
PointRenderer::~PointRenderer() = default;

Expected<std::unique_ptr<PointRenderer>> PointRenderer::create() {
    auto program = detail::build_program(kVertexShader, kFragmentShader);
    if (!program) return fail(program.error());
    std::unique_ptr<PointRenderer> renderer(new PointRenderer());
    Gpu& gpu = *renderer->gpu_;
    gpu.program = *program;
    gpu.mvp = glGetUniformLocation(gpu.program, "u_mvp");
    gpu.chunk_color = glGetUniformLocation(gpu.program, "u_chunk_color");
    gpu.use_vertex_color = glGetUniformLocation(gpu.program, "u_use_vertex_color");
    gpu.highlight = glGetUniformLocation(gpu.program, "u_highlight");
    return renderer;
}

void shuffle_chunk_points(PointCloud& cloud, std::int64_t id) {
    std::mt19937_64 rng(0x5eed0000ull + static_cast<std::uint64_t>(id));
    const bool colors = cloud.has_colors();
    for (std::size_t i = cloud.size(); i > 1; --i) {
        const std::size_t j = std::uniform_int_distribution<std::size_t>(0, i - 1)(rng);
        std::swap(cloud.positions[i - 1], cloud.positions[j]);
        if (colors) std::swap(cloud.colors[i - 1], cloud.colors[j]);
    }
}

void PointRenderer::add_chunk(std::int64_t id, PointCloud cloud,
                              const Eigen::Isometry3d& T_world_chunk, ChunkUpload upload) {
    remove_chunk(id);
    if (cloud.empty()) return;
    auto chunk = std::make_unique<Chunk>();
    const Bounds b = local_bounds(cloud);
    chunk->local_sphere = {.centre_m = (0.5f * (b.min + b.max)).cast<double>(),
                           .radius_m = 0.5 * static_cast<double>(b.extent().norm())};
    chunk->count = cloud.size();
    chunk->has_colors = cloud.has_colors();
    chunk->origin_m = cloud.origin_m;
    chunk->T_world_chunk = T_world_chunk;
    if (!upload.shuffled) shuffle_chunk_points(cloud, id);
    if (upload.points_per_step == 0 || upload.points_per_step >= cloud.size()) {
        chunk->buffers.upload(cloud.positions, cloud.colors);
        chunk->uploaded = chunk->count;
        ++revision_;
        // `cloud` (the only CPU copy) is freed on return.
    } else {
        chunk->buffers.allocate(chunk->count, chunk->has_colors);
        chunk->points_per_step = upload.points_per_step;
        chunk->pending = std::move(cloud);  // the only CPU copy, freed when uploaded
    }
    chunks_[id] = std::move(chunk);
}

bool PointRenderer::upload_step() {
    for (auto& [id, c] : chunks_) {
        if (c->complete()) continue;
        const std::size_t end = std::min(c->count, c->uploaded + c->points_per_step);
        c->buffers.fill(c->pending, c->uploaded, end);
        c->uploaded = end;
        if (c->complete()) {
            c->pending = PointCloud{};
            ++revision_;  // drawn from now on
        }
        return uploading();
    }
    return false;
}

bool PointRenderer::uploading() const {
    return std::any_of(chunks_.begin(), chunks_.end(),
                       [](const auto& c) { return !c.second->complete(); });
}

void PointRenderer::set_pose(std::int64_t id, const Eigen::Isometry3d& T_world_chunk) {
    if (auto it = chunks_.find(id); it != chunks_.end()) {
        it->second->T_world_chunk = T_world_chunk;
        ++revision_;
    }
}

void PointRenderer::set_style(std::int64_t id, const ChunkStyle& style) {
    auto it = chunks_.find(id);
    if (it == chunks_.end() || it->second->style == style) return;
    it->second->style = style;
    ++revision_;
}

void PointRenderer::remove_chunk(std::int64_t id) {
    if (chunks_.erase(id) > 0) ++revision_;
}

void PointRenderer::set_hole_markers(std::span<const HoleMarker> holes) {
    ++revision_;
    gpu_->markers.release();
    const detail::MarkerLines lines = detail::hole_marker_lines(holes);
    gpu_->marker_vertices = lines.vertices.size();
    gpu_->markers_origin_m = lines.origin_m;
    if (lines.vertices.empty()) return;
    gpu_->markers.upload(lines.vertices, {});
}

BoundingSphere PointRenderer::bounds() const {
    // Union of the chunks' spheres: centre = mean of centres weighted by points, radius
    // covers every sphere.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double weight = 0.0;
    for (const auto& [id, c] : chunks_) {
        if (!c->style.visible || !c->complete()) continue;
        centre += static_cast<double>(c->count) *
                  (c->T_world_chunk * (c->origin_m + c->local_sphere.centre_m));
        weight += static_cast<double>(c->count);
    }
    if (weight == 0.0) return {};
    centre /= weight;
    double radius = 0.0;
    for (const auto& [id, c] : chunks_) {
        if (!c->style.visible || !c->complete()) continue;
        const Eigen::Vector3d ci = c->T_world_chunk * (c->origin_m + c->local_sphere.centre_m);
        radius = std::max(radius, (ci - centre).norm() + c->local_sphere.radius_m);
    }
    return {.centre_m = centre, .radius_m = radius};
}

std::size_t PointRenderer::total_points() const {
    std::size_t n = 0;
    for (const auto& [id, c] : chunks_) n += c->complete() ? c->count : 0;
    return n;
}

std::size_t PointRenderer::gpu_bytes() const {
    std::size_t bytes = 0;
    for (const auto& [id, c] : chunks_) bytes += c->uploaded * (c->has_colors ? 15 : 12);
    return bytes;
}

namespace {

/// P · V · T_world_chunk · translate(origin), computed in double, used in float.
Eigen::Matrix4f model_view_projection(const Eigen::Matrix4d& PV, const Eigen::Isometry3d& T,
                                      const Eigen::Vector3d& origin_m) {
    const Eigen::Isometry3d M = T * Eigen::Translation3d(origin_m);
    return (PV * M.matrix()).cast<float>();
}

}  // namespace

void PointRenderer::draw_chunk(const Chunk& c, const Eigen::Matrix4d& PV, const DrawConfig& config,
                               std::size_t begin, std::size_t end, float size_px) const {
    const Gpu& gpu = *gpu_;
    const Eigen::Matrix4f mvp = model_view_projection(PV, c.T_world_chunk, c.origin_m);
    glUniformMatrix4fv(gpu.mvp, 1, GL_FALSE, mvp.data());
    const bool per_point = config.color_mode == ColorMode::kByCoverage && c.has_colors;
    const Rgb8 chunk_rgb =
        config.color_mode == ColorMode::kByQuality ? c.style.quality_color : c.style.scan_color;
    const Eigen::Vector3f rgb = config.color_mode == ColorMode::kByCoverage
                                    ? Eigen::Vector3f::Constant(kNoColorGrey)
                                    : to_float_rgb(chunk_rgb);
    glUniform3f(gpu.chunk_color, rgb.x(), rgb.y(), rgb.z());
    glUniform1i(gpu.use_vertex_color, per_point ? 1 : 0);
    glUniform1f(gpu.highlight, c.style.highlighted ? 1.0f : 0.0f);
    glPointSize(c.style.highlighted ? size_px + 1.0f : size_px);
    glBindVertexArray(c.buffers.vao);
    glDrawArrays(GL_POINTS, static_cast<GLint>(begin), static_cast<GLsizei>(end - begin));
}

void PointRenderer::draw_markers(const Eigen::Matrix4d& PV) const {
    const Gpu& gpu = *gpu_;
    if (gpu.marker_vertices == 0) return;
    const Eigen::Matrix4f mvp =
        model_view_projection(PV, Eigen::Isometry3d::Identity(), gpu.markers_origin_m);
    glUniformMatrix4fv(gpu.mvp, 1, GL_FALSE, mvp.data());
    const Eigen::Vector3f rgb = to_float_rgb(kHoleColor);
    glUniform3f(gpu.chunk_color, rgb.x(), rgb.y(), rgb.z());
    glUniform1i(gpu.use_vertex_color, 0);
    glUniform1f(gpu.highlight, 0.0f);
    glDisable(GL_DEPTH_TEST);  // a hole marker must show even behind points
    glBindVertexArray(gpu.markers.vao);
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(gpu.marker_vertices));
}

DrawStats PointRenderer::draw(const OrbitCamera& camera, double aspect, const DrawConfig& config) {
    std::vector<const Chunk*> visible;
    std::vector<std::size_t> sizes;
    for (const auto& [id, c] : chunks_) {
        if (!c->style.visible || !c->complete()) continue;
        visible.push_back(c.get());
        sizes.push_back(c->count);
    }
    // This frame's slice of every chunk: [begin_i, end_i) of its shuffled points.
    const std::vector<std::size_t> begins = points_to_draw(sizes, config.slice_begin_points);
    const std::vector<std::size_t> ends =
        points_to_draw(sizes, config.slice_begin_points + config.budget_points);
    DrawStats stats;
    std::size_t drawn_total = 0;
    for (std::size_t i = 0; i < visible.size(); ++i) {
        stats.points_visible += sizes[i];
        stats.points_drawn += ends[i] - std::min(begins[i], ends[i]);
        drawn_total += ends[i];
    }
    stats.points_in_image = drawn_total;
    stats.complete = drawn_total == stats.points_visible;
    const double fraction =
        stats.points_visible == 0
            ? 1.0
            : static_cast<double>(stats.points_drawn) / static_cast<double>(stats.points_visible);
    const float size_px = config.enlarge_thinned
                              ? thinned_point_size_px(config.base_point_size_px, fraction)
                              : config.base_point_size_px;
    const Eigen::Matrix4d PV = camera.projection(aspect) * camera.view().matrix();
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_PROGRAM_POINT_SIZE);  // glPointSize per chunk: llvmpipe's fast path
    glUseProgram(gpu_->program);
    for (std::size_t i = 0; i < visible.size(); ++i) {
        if (ends[i] <= begins[i]) continue;
        draw_chunk(*visible[i], PV, config, begins[i], ends[i], size_px);
        ++stats.chunks_drawn;
    }
    draw_markers(PV);
    glBindVertexArray(0);
    glUseProgram(0);
    return stats;
}

}  // namespace anascan::gui
