#include "anascan/sim/stone_block.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "hash_random.hpp"
#include "stone_relief.hpp"

namespace anascan::sim {
namespace {

using detail::FaceFrame;

// Lattice of the undisplaced box surface: n[axis] cells along each axis.
struct Lattice {
    Eigen::Vector3i cells;
    Eigen::Vector3d half_m;

    Eigen::Vector3d position(const Eigen::Vector3i& ijk) const {
        const Eigen::Vector3d t = ijk.cast<double>().cwiseQuotient(cells.cast<double>());
        return (2.0 * t - Eigen::Vector3d::Ones()).cwiseProduct(half_m);
    }
    std::int64_t key(const Eigen::Vector3i& ijk) const {
        return (static_cast<std::int64_t>(ijk.x()) * (cells.y() + 1) + ijk.y()) * (cells.z() + 1) +
               ijk.z();
    }
};

// A chip: the corner along one edge cut off by a rough, elliptically bounded chamfer.
struct Chip {
    int axis = 0;                ///< The edge runs along this axis.
    Eigen::Vector3d edge_point;  ///< A point of the edge line (its coordinate on axis: 0).
    Eigen::Vector3d outward;     ///< Unit bisector of the two face normals.
    double centre_m = 0.0, half_length_m = 0.0, depth_m = 0.0;
    std::uint64_t seed = 0;
};

std::vector<Chip> make_chips(const StoneBlockConfig& config, const Eigen::Vector3d& half_m) {
    std::vector<Chip> chips;
    for (int c = 0; c < config.chip_count; ++c) {
        auto draw = [&](int k) {
            return detail::unit_from_hash(detail::hash3(config.seed, 500 + c, k));
        };
        Chip chip{.axis = static_cast<int>(3.0 * draw(0)) % 3};
        const int o1 = (chip.axis + 1) % 3, o2 = (chip.axis + 2) % 3;
        const double s1 = draw(1) < 0.5 ? -1.0 : 1.0, s2 = draw(2) < 0.5 ? -1.0 : 1.0;
        chip.edge_point = Eigen::Vector3d::Zero();
        chip.edge_point[o1] = s1 * half_m[o1];
        chip.edge_point[o2] = s2 * half_m[o2];
        chip.outward = Eigen::Vector3d::Zero();
        chip.outward[o1] = s1 / std::sqrt(2.0);
        chip.outward[o2] = s2 / std::sqrt(2.0);
        chip.half_length_m = config.chip_max_half_length_m * (0.3 + 0.7 * draw(3));
        chip.centre_m =
            (2.0 * draw(4) - 1.0) * std::max(0.0, half_m[chip.axis] - chip.half_length_m);
        chip.depth_m = config.chip_max_depth_m * (0.3 + 0.7 * draw(5));
        chip.seed = detail::hash3(config.seed, 600 + c);
        chips.push_back(chip);
    }
    return chips;
}

// Moves p onto the chip's fracture surface when it lies in the chipped-off corner.
void apply_chip(const Chip& chip, Eigen::Vector3d& p) {
    const double t = (p[chip.axis] - chip.centre_m) / chip.half_length_m;
    if (std::abs(t) >= 1.0) return;
    const double roughness = 0.8 + 0.4 * detail::value_noise(chip.seed, p[chip.axis] / 0.01, 0.0);
    const double depth_m = chip.depth_m * std::sqrt(1.0 - t * t) * roughness;
    const double limit = -depth_m / std::sqrt(2.0);
    const double h = chip.outward.dot(p - chip.edge_point);
    if (h > limit) p += (limit - h) * chip.outward;
}

// A lost corner: the corner at signs s cut off by a rough plane across its diagonal.
struct LostCorner {
    Eigen::Vector3d corner, outward;
    double depth_m = 0.0;
    std::uint64_t seed = 0;
};

std::vector<LostCorner> make_lost_corners(const StoneBlockConfig& config,
                                          const Eigen::Vector3d& half_m) {
    std::vector<LostCorner> corners;
    for (int c = 0; c < config.lost_corner_count; ++c) {
        auto draw = [&](int k) {
            return detail::unit_from_hash(detail::hash3(config.seed, 700 + c, k));
        };
        Eigen::Vector3d signs;
        for (int a = 0; a < 3; ++a) signs[a] = draw(a) < 0.5 ? -1.0 : 1.0;
        corners.push_back({.corner = signs.cwiseProduct(half_m),
                           .outward = signs / std::sqrt(3.0),
                           .depth_m = config.lost_corner_max_depth_m * (0.5 + 0.5 * draw(3)),
                           .seed = detail::hash3(config.seed, 800 + c)});
    }
    return corners;
}

void apply_lost_corner(const LostCorner& lost, Eigen::Vector3d& p) {
    const double rough =
        0.9 + 0.2 * detail::value_noise(lost.seed, p.x() / 0.02 + p.z() / 0.03, p.y() / 0.02);
    const double limit = -lost.depth_m * rough;
    const double h = lost.outward.dot(p - lost.corner);
    if (h > limit) p += (limit - h) * lost.outward;
}

int dominant_axis(const Eigen::Vector3d& v) {
    int axis = 0;
    v.cwiseAbs().maxCoeff(&axis);
    return axis;
}

// Number of lattice coordinates of ijk on the box boundary (1: face interior).
int boundary_count(const Lattice& lattice, const Eigen::Vector3i& ijk) {
    int count = 0;
    for (int a = 0; a < 3; ++a) count += (ijk[a] == 0 || ijk[a] == lattice.cells[a]) ? 1 : 0;
    return count;
}

struct MeshBuilder {
    const StoneBlockConfig& config;
    Lattice lattice;
    std::vector<Chip> chips;
    std::vector<LostCorner> lost_corners;
    Mesh mesh;
    std::unordered_map<std::int64_t, int> index_of;

    int vertex(const FaceFrame& frame, const Eigen::Vector3i& ijk) {
        const auto [it, inserted] = index_of.try_emplace(lattice.key(ijk), 0);
        if (!inserted) return it->second;
        Eigen::Vector3d p = lattice.position(ijk);
        if (boundary_count(lattice, ijk) == 1)
            p -= detail::face_relief_m(config, frame, p.dot(frame.a), p.dot(frame.b)) * frame.n;
        for (const Chip& chip : chips) apply_chip(chip, p);
        for (const LostCorner& lost : lost_corners) apply_lost_corner(lost, p);
        it->second = static_cast<int>(mesh.vertices.positions.size());
        mesh.vertices.positions.push_back(p.cast<float>());
        return it->second;
    }

    // Lattice index of face grid point (ia, ib).
    Eigen::Vector3i face_ijk(const FaceFrame& frame, int ia, int ib) const {
        Eigen::Vector3i ijk = Eigen::Vector3i::Zero();
        const int n_axis = dominant_axis(frame.n), a_axis = dominant_axis(frame.a);
        const int b_axis = 3 - n_axis - a_axis;
        ijk[n_axis] = frame.n[n_axis] > 0 ? lattice.cells[n_axis] : 0;
        ijk[a_axis] = frame.a[a_axis] > 0 ? ia : lattice.cells[a_axis] - ia;
        ijk[b_axis] = frame.b[b_axis] > 0 ? ib : lattice.cells[b_axis] - ib;
        return ijk;
    }

    void add_face(const FaceFrame& frame) {
        const int na = static_cast<int>(frame.a.cwiseAbs().dot(lattice.cells.cast<double>()));
        const int nb = static_cast<int>(frame.b.cwiseAbs().dot(lattice.cells.cast<double>()));
        std::vector<int> ids(static_cast<std::size_t>((na + 1) * (nb + 1)));
        for (int ib = 0; ib <= nb; ++ib)
            for (int ia = 0; ia <= na; ++ia)
                ids[ib * (na + 1) + ia] = vertex(frame, face_ijk(frame, ia, ib));
        for (int ib = 0; ib < nb; ++ib) {
            for (int ia = 0; ia < na; ++ia) {
                const int v00 = ids[ib * (na + 1) + ia], v10 = ids[ib * (na + 1) + ia + 1];
                const int v01 = ids[(ib + 1) * (na + 1) + ia],
                          v11 = ids[(ib + 1) * (na + 1) + ia + 1];
                mesh.triangles.emplace_back(v00, v10, v11);
                mesh.triangles.emplace_back(v00, v11, v01);
            }
        }
    }
};

void add_vertex_normals(Mesh& mesh) {
    std::vector<Eigen::Vector3d> sums(mesh.vertices.size(), Eigen::Vector3d::Zero());
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices.positions[t[0]].cast<double>();
        const Eigen::Vector3d n = (mesh.vertices.positions[t[1]].cast<double>() - a)
                                      .cross(mesh.vertices.positions[t[2]].cast<double>() - a);
        for (int k = 0; k < 3; ++k) sums[t[k]] += n;  // Area weighted.
    }
    mesh.vertices.normals.resize(sums.size());
    for (std::size_t v = 0; v < sums.size(); ++v)
        mesh.vertices.normals[v] = sums[v].normalized().cast<float>();
}

}  // namespace

Eigen::Vector3d face_normal(BlockFace face) {
    return detail::face_frame(face, Eigen::Vector3d::Ones()).n;
}

Mesh make_stone_block(const StoneBlockConfig& config) {
    const Eigen::Vector3d half_m = 0.5 * config.size_m.cwiseAbs();
    const double step = std::max(config.grid_step_m, 1e-4);
    Lattice lattice{.cells = (2.0 * half_m / step).array().round().max(2.0).cast<int>().matrix(),
                    .half_m = half_m};
    MeshBuilder builder{.config = config,
                        .lattice = lattice,
                        .chips = make_chips(config, half_m),
                        .lost_corners = make_lost_corners(config, half_m)};
    for (int f = 0; f < kBlockFaceCount; ++f)
        builder.add_face(detail::face_frame(static_cast<BlockFace>(f), half_m));
    add_vertex_normals(builder.mesh);
    return std::move(builder.mesh);
}

}  // namespace anascan::sim
