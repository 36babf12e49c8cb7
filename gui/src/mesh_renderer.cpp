#include "anascan/gui/mesh_renderer.hpp"

#include <vector>

#include "shader_program.hpp"

namespace anascan::gui {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_color;
uniform mat4 u_mvp;
uniform mat3 u_view_rotation;
out vec3 v_color;
out vec3 v_normal_view;
void main() {
    gl_Position = u_mvp * vec4(a_position, 1.0);
    v_color = a_color;
    v_normal_view = u_view_rotation * a_normal;
}
)";

// A headlight, two-sided: a face toward the camera is lit fully, one seen edge-on is dark
// but never black (the ambient share), so a back face seen through a hole still reads.
constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 v_color;
in vec3 v_normal_view;
out vec4 frag_color;
void main() {
    float facing = abs(normalize(v_normal_view).z);
    frag_color = vec4(v_color * (0.3 + 0.7 * facing), 1.0);
}
)";

static_assert(sizeof(Eigen::Vector3i) == 3 * sizeof(GLuint), "triangles upload as packed indices");

constexpr Rgb8 kUnclassedGrey{178, 172, 160};

/// Area-weighted vertex normals of the triangles.
std::vector<Eigen::Vector3f> vertex_normals(const Mesh& mesh) {
    std::vector<Eigen::Vector3f> n(mesh.vertices.size(), Eigen::Vector3f::Zero());
    const auto& p = mesh.vertices.positions;
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3f face = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
        for (int k = 0; k < 3; ++k) n[std::size_t(t[k])] += face;
    }
    for (Eigen::Vector3f& v : n) v = v.norm() > 0.0f ? v.normalized() : Eigen::Vector3f::UnitZ();
    return n;
}

template <class T>
GLuint array_buffer(GLuint index, const std::vector<T>& data, GLint components, GLenum type) {
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, components, type, type == GL_UNSIGNED_BYTE ? GL_TRUE : GL_FALSE, 0,
                          nullptr);
    return buffer;
}

}  // namespace

struct MeshRenderer::Gpu {
    GLuint program = 0;
    GLint mvp = -1, view_rotation = -1;
    GLuint vao = 0, positions = 0, normals = 0, colors = 0, indices = 0;
    std::size_t index_count = 0;
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
    BoundingSphere sphere;
    void release_mesh() {
        for (GLuint* b : {&positions, &normals, &colors, &indices})
            if (*b != 0) glDeleteBuffers(1, b);
        if (vao != 0) glDeleteVertexArrays(1, &vao);
        vao = positions = normals = colors = indices = 0;
        index_count = 0;
        sphere = {};
    }
    ~Gpu() {
        release_mesh();
        if (program != 0) glDeleteProgram(program);
    }
};

MeshRenderer::MeshRenderer() : gpu_(std::make_unique<Gpu>()) {}
MeshRenderer::~MeshRenderer() = default;

Expected<std::unique_ptr<MeshRenderer>> MeshRenderer::create() {
    auto program = detail::build_program(kVertexShader, kFragmentShader);
    if (!program) return fail(program.error());
    std::unique_ptr<MeshRenderer> renderer(new MeshRenderer());
    Gpu& gpu = *renderer->gpu_;
    gpu.program = *program;
    gpu.mvp = glGetUniformLocation(gpu.program, "u_mvp");
    gpu.view_rotation = glGetUniformLocation(gpu.program, "u_view_rotation");
    return renderer;
}

void MeshRenderer::set_mesh(const Mesh& mesh) {
    Gpu& gpu = *gpu_;
    gpu.release_mesh();
    const PointCloud& v = mesh.vertices;
    if (v.empty() || mesh.triangles.empty()) return;
    const bool has_normals = v.normals.size() == v.size();
    const std::vector<Eigen::Vector3f> normals = has_normals ? v.normals : vertex_normals(mesh);
    const std::vector<Rgb8> colors =
        v.colors.size() == v.size() ? v.colors : std::vector<Rgb8>(v.size(), kUnclassedGrey);
    glGenVertexArrays(1, &gpu.vao);
    glBindVertexArray(gpu.vao);
    gpu.positions = array_buffer(0, v.positions, 3, GL_FLOAT);
    gpu.normals = array_buffer(1, normals, 3, GL_FLOAT);
    gpu.colors = array_buffer(2, colors, 3, GL_UNSIGNED_BYTE);
    glGenBuffers(1, &gpu.indices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.indices);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.triangles.size() * sizeof(Eigen::Vector3i)),
                 mesh.triangles.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    gpu.index_count = 3 * mesh.triangles.size();
    gpu.origin_m = v.origin_m;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (const Eigen::Vector3f& p : v.positions) {
        lo = lo.cwiseMin(p.cast<double>());
        hi = hi.cwiseMax(p.cast<double>());
    }
    gpu.sphere = {.centre_m = v.origin_m + 0.5 * (lo + hi), .radius_m = 0.5 * (hi - lo).norm()};
}

bool MeshRenderer::has_mesh() const { return gpu_->index_count > 0; }
std::size_t MeshRenderer::triangles() const { return gpu_->index_count / 3; }
BoundingSphere MeshRenderer::bounds() const { return gpu_->sphere; }

void MeshRenderer::draw(const OrbitCamera& camera, double aspect) const {
    const Gpu& gpu = *gpu_;
    if (gpu.index_count == 0) return;
    const Eigen::Isometry3d view = camera.view();
    // P · V · translate(origin) in double, used in float: site coordinates stay exact.
    const Eigen::Matrix4f mvp =
        (camera.projection(aspect) * (view * Eigen::Translation3d(gpu.origin_m)).matrix())
            .cast<float>();
    const Eigen::Matrix3f rotation = view.linear().cast<float>();
    glEnable(GL_DEPTH_TEST);
    glUseProgram(gpu.program);
    glUniformMatrix4fv(gpu.mvp, 1, GL_FALSE, mvp.data());
    glUniformMatrix3fv(gpu.view_rotation, 1, GL_FALSE, rotation.data());
    glBindVertexArray(gpu.vao);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(gpu.index_count), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace anascan::gui
