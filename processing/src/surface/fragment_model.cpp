#include "anascan/processing/surface/fragment_model.hpp"

namespace anascan {

bool FragmentModel::consistent() const {
    const std::size_t n = mesh.vertices.size();
    return mesh.vertices.attributes_consistent() && support_distance_m.size() == n &&
           support_scans.size() == n && vertex_class.size() == n &&
           triangle_class.size() == mesh.triangles.size();
}

FragmentModel select_triangles(const FragmentModel& model, const std::vector<bool>& keep) {
    const std::size_t n = model.mesh.vertices.size();
    std::vector<int> new_index(n, -1);
    std::vector<std::size_t> kept_vertices;
    FragmentModel out;
    out.support_threshold_m = model.support_threshold_m;
    for (std::size_t t = 0; t < model.mesh.triangles.size(); ++t) {
        if (!keep[t]) continue;
        Eigen::Vector3i tri = model.mesh.triangles[t];
        for (int k = 0; k < 3; ++k) {
            int& slot = new_index[tri[k]];
            if (slot < 0) {
                slot = static_cast<int>(kept_vertices.size());
                kept_vertices.push_back(static_cast<std::size_t>(tri[k]));
            }
            tri[k] = slot;
        }
        out.mesh.triangles.push_back(tri);
        out.triangle_class.push_back(model.triangle_class[t]);
    }
    out.mesh.vertices = select(model.mesh.vertices, kept_vertices);
    for (const std::size_t v : kept_vertices) {
        out.support_distance_m.push_back(model.support_distance_m[v]);
        out.support_scans.push_back(model.support_scans[v]);
        out.vertex_class.push_back(model.vertex_class[v]);
    }
    return out;
}

std::vector<SurfaceClass> triangle_classes_from_vertices(
    const Mesh& mesh, std::span<const SurfaceClass> vertex_class) {
    std::vector<SurfaceClass> out(mesh.triangles.size());
    for (std::size_t t = 0; t < out.size(); ++t) {
        int measured = 0;
        for (int k = 0; k < 3; ++k)
            measured += vertex_class[std::size_t(mesh.triangles[t][k])] == SurfaceClass::kMeasured;
        out[t] = measured >= 2 ? SurfaceClass::kMeasured : SurfaceClass::kInterpolated;
    }
    return out;
}

Rgb8 surface_class_color(SurfaceClass c) {
    return c == SurfaceClass::kMeasured ? Rgb8{178, 172, 160} : Rgb8{235, 120, 30};
}

void colour_by_class(FragmentModel& model) {
    model.mesh.vertices.colors.resize(model.mesh.vertices.size());
    for (std::size_t v = 0; v < model.vertex_class.size(); ++v)
        model.mesh.vertices.colors[v] = surface_class_color(model.vertex_class[v]);
}

}  // namespace anascan
