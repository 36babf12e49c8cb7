#include "anascan/processing/reassembly/block_features.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "feature_steps.hpp"

namespace anascan::reassembly {
namespace {

// Median distance to the nearest other point over an even sample of the points.
double median_spacing(std::span<const Eigen::Vector3f> points, const KdTree& tree) {
    const std::size_t stride = std::max<std::size_t>(1, points.size() / 2000);
    std::vector<double> d;
    std::vector<Neighbor> nn;
    for (std::size_t i = 0; i < points.size(); i += stride) {
        tree.knn(points[i], 2, nn);
        if (nn.size() == 2) d.push_back(std::sqrt(double(nn[1].distance_sq_m2)));
    }
    if (d.empty()) return 0.0;
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    return d[d.size() / 2];
}

std::vector<int> point_faces(std::size_t n, const std::vector<detail::FaceBuild>& faces) {
    std::vector<int> out(n, -1);
    for (const detail::FaceBuild& f : faces)
        for (std::size_t i : f.inliers) out[i] = f.face.id;
    return out;
}

// The status once faces and edges are known (faces and edges cleared unless matchable).
void set_status(BlockFeatures& out, const BlockFeatureConfig& config) {
    if (out.faces.empty()) {
        out.status = BlockStatus::kNoPlanarFace;
        out.message =
            "no planar face of at least " + std::to_string(config.faces.min_face_area_m2) + " m2";
    } else if (out.faces.size() < 2 || out.edges.empty()) {
        out.status = BlockStatus::kTooFewFaces;
        out.message = std::to_string(out.faces.size()) + " planar face(s), none meeting another";
    } else {
        std::vector<double> rms;
        for (const PlanarFace& f : out.faces) rms.push_back(f.rms_m);
        std::nth_element(rms.begin(), rms.begin() + rms.size() / 2, rms.end());
        const double median_rms = rms[rms.size() / 2];
        std::size_t on_faces = 0;
        for (int f : out.point_face) on_faces += f >= 0 ? 1 : 0;
        const double share = double(on_faces) / double(std::max<std::size_t>(1, out.num_points));
        if (median_rms > config.max_rms_factor * config.faces.epsilon_m || share < 0.2) {
            out.status = BlockStatus::kTooNoisy;
            out.message = "only " + std::to_string(int(100 * share)) +
                          "% of the points on planar faces (median RMS " +
                          std::to_string(1000 * median_rms) + " mm): too noisy to match";
        }
    }
    if (out.status != BlockStatus::kOk && out.status != BlockStatus::kNonManifold) {
        out.edges.clear();
    }
}

}  // namespace

bool mesh_vertex_normals(const Mesh& mesh, std::vector<Eigen::Vector3f>& normals) {
    std::vector<Eigen::Vector3d> sums(mesh.vertices.size(), Eigen::Vector3d::Zero());
    std::vector<std::uint64_t> edges;  // (min, max) vertex pairs, sorted to count repeats.
    edges.reserve(3 * mesh.triangles.size());
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices.positions[t[0]].cast<double>();
        const Eigen::Vector3d n = (mesh.vertices.positions[t[1]].cast<double>() - a)
                                      .cross(mesh.vertices.positions[t[2]].cast<double>() - a);
        for (int k = 0; k < 3; ++k) {
            sums[t[k]] += n;
            const auto u = std::uint64_t(std::uint32_t(t[k])),
                       v = std::uint64_t(std::uint32_t(t[(k + 1) % 3]));
            edges.push_back(std::min(u, v) << 32 | std::max(u, v));
        }
    }
    normals.resize(sums.size());
    for (std::size_t v = 0; v < sums.size(); ++v)
        normals[v] = sums[v].norm() > 0 ? Eigen::Vector3f(sums[v].normalized().cast<float>())
                                        : Eigen::Vector3f::Zero();
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 2; i < edges.size(); ++i)
        if (edges[i] == edges[i - 2]) return false;
    return true;
}

std::vector<int> BlockFeatures::neighbours(int face) const {
    std::vector<int> out;
    for (const FaceEdge& e : edges)
        if (e.from == face) out.push_back(e.to);
    return out;
}

BlockFeatures extract_block_features(const PointCloud& cloud, const BlockFeatureConfig& config) {
    BlockFeatures out;
    out.num_points = cloud.size();
    if (cloud.empty()) {
        out.status = BlockStatus::kEmpty;
        out.message = "no points";
        return out;
    }
    if (!cloud.has_normals() || cloud.normals.size() != cloud.size()) {
        out.status = BlockStatus::kNoNormals;
        out.message = "the cloud has no normals: estimate and orient them first";
        return out;
    }
    const KdTree tree(cloud.positions);
    const detail::FeatureInput in{.points = cloud.positions,
                                  .normals = cloud.normals,
                                  .tree = tree,
                                  .spacing_m = median_spacing(cloud.positions, tree)};
    out.spacing_m = in.spacing_m;
    std::vector<detail::FaceBuild> faces = detail::find_faces(in, config.faces);
    out.edges = detail::face_adjacency(in, faces, config.adjacency);
    detail::snap_to_neighbours(faces, out.edges, config.adjacency.band_m);
    out.point_face = point_faces(cloud.size(), faces);
    detail::face_roughness(in, out.point_face, faces, config.roughness);
    detail::face_holes(in, faces, config.holes);
    for (detail::FaceBuild& f : faces) out.faces.push_back(std::move(f.face));
    out.message = std::to_string(out.faces.size()) + " faces, " +
                  std::to_string(out.edges.size() / 2) + " edges";
    set_status(out, config);
    return out;
}

BlockFeatures extract_block_features(const Mesh& mesh, const BlockFeatureConfig& config) {
    if (mesh.vertices.empty() || mesh.triangles.empty()) {
        BlockFeatures out;
        out.status = BlockStatus::kEmpty;
        out.message = "empty mesh (no vertices or no triangles)";
        return out;
    }
    const int n = static_cast<int>(mesh.vertices.size());
    for (const Eigen::Vector3i& t : mesh.triangles) {
        if (t.minCoeff() < 0 || t.maxCoeff() >= n) {
            BlockFeatures out;
            out.status = BlockStatus::kBadMesh;
            out.message = "a triangle names vertex " + std::to_string(t.maxCoeff()) + " of " +
                          std::to_string(n);
            return out;
        }
    }
    PointCloud cloud;
    cloud.positions = mesh.vertices.positions;
    const bool manifold = mesh_vertex_normals(mesh, cloud.normals);
    BlockFeatures out = extract_block_features(cloud, config);
    if (!manifold && out.status == BlockStatus::kOk) {
        out.status = BlockStatus::kNonManifold;
        out.message += "; non-manifold mesh (an edge shared by more than two triangles)";
    }
    return out;
}

}  // namespace anascan::reassembly
