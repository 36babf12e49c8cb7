#pragma once
/// \file
/// The fragment model in the 3D view: its triangles in their class colours (measured stone
/// grey, interpolated orange, as in the mesh files), lit by a light at the camera so that
/// the shape reads at any angle. The mesh lies in the view's world frame (the frame the
/// scans' poses place the points in). Not thread-safe: GL thread only.

#include <memory>

#include "anascan/gui/orbit_camera.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/mesh.hpp"

namespace anascan::gui {

class MeshRenderer {
public:
    /// Compiles the shaders; needs a current OpenGL 3.3 context.
    static Expected<std::unique_ptr<MeshRenderer>> create();
    ~MeshRenderer();
    MeshRenderer(const MeshRenderer&) = delete;
    MeshRenderer& operator=(const MeshRenderer&) = delete;

    /// Uploads the mesh (replacing the one shown). Without colours it is drawn stone grey;
    /// without normals (one per vertex) they are computed from the triangles.
    void set_mesh(const Mesh& mesh);
    bool has_mesh() const;
    std::size_t triangles() const;
    /// Bounding sphere of the mesh (radius 0 when none).
    BoundingSphere bounds() const;
    /// Draws into the current viewport, with depth test (the caller cleared it).
    void draw(const OrbitCamera& camera, double aspect) const;

private:
    struct Gpu;
    MeshRenderer();
    std::unique_ptr<Gpu> gpu_;
};

}  // namespace anascan::gui
