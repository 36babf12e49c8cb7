// Coverage, the surface estimate: the convex hull of the stone's points by Qhull (the
// reentrant libqhull_r of Debian), triangulated ('Qt'), triangles turned outward by the
// facet normals. Qhull's messages go to a memory stream, never to the terminal.

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "coverage/steps.hpp"

namespace anascan::coverage_detail {
namespace {

// The triangles of a finished Qhull run, outward (vertex indices = input point indices).
std::vector<Eigen::Vector3i> hull_triangles(qhT* qh) {
    std::vector<Eigen::Vector3i> triangles;
    facetT* facet = nullptr;
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FORALLfacets {
        if (facet->upperdelaunay || qh_setsize(qh, facet->vertices) != 3) continue;
        Eigen::Vector3i t;
        Eigen::Vector3d p[3];
        int k = 0;
        FOREACHvertex_(facet->vertices) {
            t[k] = qh_pointid(qh, vertex->point);
            p[k] = Eigen::Vector3d(vertex->point[0], vertex->point[1], vertex->point[2]);
            ++k;
        }
        const Eigen::Vector3d normal(facet->normal[0], facet->normal[1], facet->normal[2]);
        if ((p[1] - p[0]).cross(p[2] - p[0]).dot(normal) < 0.0) std::swap(t[1], t[2]);
        triangles.push_back(t);
    }
    return triangles;
}

}  // namespace

Mesh convex_hull(std::span<const Eigen::Vector3f> points) {
    Mesh mesh;
    if (points.size() < 4) return mesh;
    std::vector<coordT> coords;
    coords.reserve(points.size() * 3);
    for (const Eigen::Vector3f& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
    char* messages = nullptr;
    std::size_t message_size = 0;
    FILE* sink = open_memstream(&messages, &message_size);
    qhT qh_storage;
    qhT* qh = &qh_storage;
    qh_zero(qh, sink);
    char flags[] = "qhull Qt";
    const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False,
                                       flags, nullptr, sink);
    if (exit_code == 0) mesh.triangles = hull_triangles(qh);
    qh_freeqhull(qh, !qh_ALL);
    int current_long = 0, total_long = 0;
    qh_memfreeshort(qh, &current_long, &total_long);
    if (sink != nullptr) std::fclose(sink);
    std::free(messages);
    // Keep only the hull's vertices.
    std::vector<int> new_index(points.size(), -1);
    for (Eigen::Vector3i& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            int& index = new_index[static_cast<std::size_t>(t[k])];
            if (index < 0) {
                index = static_cast<int>(mesh.vertices.positions.size());
                mesh.vertices.positions.push_back(points[static_cast<std::size_t>(t[k])]);
            }
            t[k] = index;
        }
    return mesh;
}

}  // namespace anascan::coverage_detail
