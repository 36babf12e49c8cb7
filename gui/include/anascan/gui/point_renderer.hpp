#pragma once
/// \file
/// The OpenGL 3.3 point view: one vertex buffer per scan chunk, colour by scan / quality /
/// coverage, the newest (or selected) scan highlighted, markers at the coverage holes, and
/// level of detail (see level_of_detail.hpp).
///
/// Memory rule: the GUI never holds more than one copy of the points. add_chunk() takes the
/// cloud by value, shuffles it in place (for the LOD prefix; or the loading thread did),
/// uploads positions and colours straight from its arrays (at once, or in steps over
/// frames) and frees it; afterwards only the GPU buffers and a bounding sphere remain. Not
/// thread-safe: use it on the thread that owns the GL context.

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "anascan/gui/field_view_state.hpp"
#include "anascan/gui/orbit_camera.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::gui {

/// How one chunk is drawn.
struct ChunkStyle {
    Rgb8 scan_color{200, 200, 200};     ///< Used in ColorMode::kByScan.
    Rgb8 quality_color{200, 200, 200};  ///< Used in ColorMode::kByQuality.
    bool visible = true;                ///< Excluded scans are hidden.
    bool highlighted = false;           ///< Newest or selected scan: brighter, larger points.
    friend bool operator==(const ChunkStyle&, const ChunkStyle&) = default;
};

/// A coverage hole, drawn as a ring (radius from the area) with its normal.
struct HoleMarker {
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< World frame.
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double area_m2 = 0.0;
};

struct DrawConfig {
    ColorMode color_mode = ColorMode::kByScan;
    std::size_t budget_points = 2'000'000;  ///< LOD: at most this many points per frame.
    /// Progressive refinement: skip the points earlier frames drew (see ProgressiveView).
    std::size_t slice_begin_points = 0;
    float base_point_size_px = 2.0f;
    /// Enlarge thinned points to fill the gaps (a fresh image); off when adding detail.
    bool enlarge_thinned = true;
};

struct DrawStats {
    std::size_t points_drawn = 0;
    std::size_t points_visible = 0;  ///< Of the visible chunks, before LOD.
    int chunks_drawn = 0;
    std::size_t points_in_image = 0;  ///< This and the earlier slices.
    bool complete = false;            ///< Every visible point is now in the image.
};

/// How add_chunk uploads a chunk.
struct ChunkUpload {
    /// The cloud was shuffled already (shuffle_chunk_points, on the loading thread).
    bool shuffled = false;
    /// > 0: upload this many points per upload_step() call (one per frame), so that no frame
    /// copies a whole scan; the chunk is drawn once it is complete. 0: all at once.
    std::size_t points_per_step = 0;
};

/// The LOD shuffle add_chunk does (fixed seed per chunk id: any prefix is a uniform
/// sample), for a loading thread; then add_chunk with ChunkUpload::shuffled.
void shuffle_chunk_points(PointCloud& cloud, std::int64_t id);

class PointRenderer {
public:
    /// Compiles the shaders; needs a current OpenGL 3.3 (core or compatibility) context.
    static Expected<std::unique_ptr<PointRenderer>> create();
    ~PointRenderer();
    PointRenderer(const PointRenderer&) = delete;
    PointRenderer& operator=(const PointRenderer&) = delete;

    /// Uploads a chunk (replacing one with the same id) and frees the cloud. A point's
    /// world position is T_world_chunk · (origin_m + position). The cloud's colours, if any,
    /// are shown in ColorMode::kByCoverage (coverage samples carry green/red). Empty clouds
    /// are ignored.
    void add_chunk(std::int64_t id, PointCloud cloud, const Eigen::Isometry3d& T_world_chunk,
                   ChunkUpload upload = {});
    /// Uploads the next points_per_step points of the chunks still uploading (glBufferSubData)
    /// and frees each cloud once it is on the GPU; returns true while any remains. Once a
    /// frame.
    bool upload_step();
    /// A chunk is still being uploaded (its cloud is still in CPU memory).
    bool uploading() const;
    /// Moves a chunk (after refinement or a group merge).
    void set_pose(std::int64_t id, const Eigen::Isometry3d& T_world_chunk);
    void set_style(std::int64_t id, const ChunkStyle& style);
    void remove_chunk(std::int64_t id);
    void set_hole_markers(std::span<const HoleMarker> holes);

    /// Draws into the current viewport (the caller set glViewport and cleared).
    DrawStats draw(const OrbitCamera& camera, double aspect, const DrawConfig& config);

    /// Bounding sphere of the visible, uploaded chunks (world frame); radius 0 when empty.
    BoundingSphere bounds() const;
    std::size_t total_points() const;  ///< Of the uploaded chunks.
    /// Bytes of point data in GPU buffers (the CPU keeps none).
    std::size_t gpu_bytes() const;
    /// Changes whenever the drawn image would change for an unchanged camera (chunks, poses,
    /// styles, markers): the key of a cached view.
    std::uint64_t revision() const { return revision_; }

private:
    struct Chunk;
    struct Gpu;
    PointRenderer();
    void draw_chunk(const Chunk& c, const Eigen::Matrix4d& PV, const DrawConfig& config,
                    std::size_t begin, std::size_t end, float size_px) const;
    void draw_markers(const Eigen::Matrix4d& PV) const;
    std::uint64_t revision_ = 0;
    std::map<std::int64_t, std::unique_ptr<Chunk>> chunks_;
    std::unique_ptr<Gpu> gpu_;
};

}  // namespace anascan::gui
