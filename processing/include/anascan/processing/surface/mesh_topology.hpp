#pragma once
/// \file
/// Topology of a triangle mesh: boundary and non-manifold edges, non-manifold vertices,
/// connected components and the boundary loops (the outlines of holes).

#include <cstddef>
#include <vector>

#include "anascan/processing/core/mesh.hpp"

namespace anascan {

struct MeshTopology {
    std::size_t boundary_edges = 0;         ///< Edges used by one triangle.
    std::size_t non_manifold_edges = 0;     ///< Edges used by three or more triangles.
    std::size_t inconsistent_edges = 0;     ///< Edges whose two triangles disagree in winding.
    std::size_t non_manifold_vertices = 0;  ///< Vertices whose triangles form several fans.
    std::size_t components = 0;             ///< Edge-connected sets of triangles.
    /// Closed loops of boundary edges, each as vertex indices in order.
    std::vector<std::vector<int>> boundary_loops;
    /// Component of each triangle, 0 = the largest (by triangle count).
    std::vector<int> triangle_component;

    bool closed() const { return boundary_edges == 0 && non_manifold_edges == 0; }
    bool manifold() const {
        return non_manifold_edges == 0 && non_manifold_vertices == 0 && inconsistent_edges == 0;
    }
};

/// Analyses the mesh's triangles (degenerate triangles count as they are).
MeshTopology analyse_topology(const Mesh& mesh);

}  // namespace anascan
