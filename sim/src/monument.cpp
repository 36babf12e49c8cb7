#include "anascan/sim/monument.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "anascan/sim/scene.hpp"
#include "hash_random.hpp"

namespace anascan::sim {
namespace {

// Counter-based draws of one monument: a value depends only on (seed, stream, index).
struct Draws {
    std::uint64_t seed;
    double uniform(std::uint64_t stream, std::uint64_t index, double lo, double hi) const {
        return lo + (hi - lo) * detail::unit_from_hash(detail::hash3(seed, stream, index));
    }
};

// Block lengths of one course: drawn, scaled to the course length, redrawn until every
// length is within bounds and no vertical joint is closer than the stagger to `avoid`.
Expected<std::vector<double>> course_lengths(const MonumentConfig& c, const Draws& draws,
                                             int course, const std::vector<double>& avoid) {
    const double total_m = c.blocks_per_course * c.mean_block_length_m;
    for (int attempt = 0; attempt < 500; ++attempt) {
        std::vector<double> lengths(static_cast<std::size_t>(c.blocks_per_course));
        for (std::size_t i = 0; i < lengths.size(); ++i)
            lengths[i] = draws.uniform(10 + course, attempt * 64 + i, c.min_block_length_m,
                                       c.max_block_length_m);
        const double scale = total_m / std::accumulate(lengths.begin(), lengths.end(), 0.0);
        bool ok = true;
        double x = 0.0;
        for (std::size_t i = 0; i < lengths.size(); ++i) {
            lengths[i] *= scale;
            ok = ok && lengths[i] >= c.min_block_length_m && lengths[i] <= c.max_block_length_m;
            x += lengths[i];
            if (i + 1 == lengths.size()) break;
            for (double joint : avoid) ok = ok && std::abs(joint - x) >= c.min_joint_stagger_m;
        }
        if (ok) return lengths;
    }
    return fail(ErrorCode::kInvalidArgument, "monument " + c.name + ": no block lengths within [" +
                                                 std::to_string(c.min_block_length_m) + ", " +
                                                 std::to_string(c.max_block_length_m) +
                                                 "] m fit the course");
}

// Finishes as on the Octagon, by sharpness of their tool marks (amplitude / wavelength²,
// which the bending energy sees): a smooth façade, pointed bed faces, anathyrosis on the
// joint faces (smooth drafted band, finer and sharper recessed centre), a rough back;
// each varied by up to 25% per block.
std::array<FaceFinish, kBlockFaceCount> monument_finishes(const Draws& draws, int block) {
    auto vary = [&](int k) { return draws.uniform(30, block * 8 + k, 0.8, 1.25); };
    const FaceFinish joint{
        .amplitude_m = 0.0015 * vary(0), .wavelength_m = 0.012, .recess_m = 0.002};
    const FaceFinish bed{.amplitude_m = 0.0025 * vary(1), .wavelength_m = 0.025};
    return {joint,
            joint,
            FaceFinish{.amplitude_m = 0.0002 * vary(2), .wavelength_m = 0.02},
            FaceFinish{.amplitude_m = 0.006 * vary(3), .wavelength_m = 0.02},
            bed,
            bed};
}

MonumentBlock make_block(const MonumentConfig& c, const Draws& draws, int course, int index,
                         const Eigen::Vector3d& min_corner_m, const Eigen::Vector3d& size_m) {
    const int serial = course * 100 + index;
    MonumentBlock block{.id = "c" + std::to_string(course) + "b" + std::to_string(index),
                        .course = course};
    StoneBlockConfig& b = block.config;
    b.size_m = size_m;
    b.grid_step_m = c.grid_step_m;
    b.finishes = monument_finishes(draws, serial);
    b.margin_m = 0.04;
    b.clamp_holes.clear();
    b.dowel_holes.clear();
    b.ornament.enabled = false;
    b.seed = detail::hash3(c.seed, 40, static_cast<std::uint64_t>(serial));
    block.T_monument_block = Pose::Identity();
    block.T_monument_block.translation() = min_corner_m + 0.5 * size_m;
    return block;
}

// The façade's ornament band on the lowest course and the moulding on the top course,
// both continuous across the vertical joints.
void add_facade_lines(const MonumentConfig& c, Monument& m) {
    for (MonumentBlock& block : m.blocks) {
        if (block.course == 0) {
            block.config.ornament =
                OrnamentBand{.enabled = true,
                             .face = BlockFace::kPosY,
                             .top_offset_m = 0.12,
                             .height_m = 0.08,
                             .phase_m = block.T_monument_block.translation().x(),
                             .run_to_edges = true};
        }
        if (block.course == c.courses - 1)
            block.config.moulding = Moulding{.enabled = true, .face = BlockFace::kPosY};
    }
}

// Π-clamp channels across the vertical joint between blocks a (left) and b (right).
void add_vertical_joint(const Draws& draws, int a, int b, Monument& m) {
    const double depth_m = m.blocks[a].config.size_m.y();
    const double offset_m = draws.uniform(50, a * 1000 + b, -0.25, 0.25) * depth_m;
    const double length_m = draws.uniform(51, a * 1000 + b, 0.10, 0.15);
    const ClampHole half{.length_m = length_m, .open_at_edge = true};
    ClampHole left = half, right = half;
    left.edge_face = BlockFace::kPosX;
    left.offset_m = offset_m;  // Along +y of the top face for the +x edge.
    right.edge_face = BlockFace::kNegX;
    right.offset_m = -offset_m;  // The -x edge runs the other way.
    m.blocks[a].config.clamp_holes.push_back(left);
    m.blocks[b].config.clamp_holes.push_back(right);
    m.joints.push_back(
        {.a = {a, BlockFace::kPosX}, .b = {b, BlockFace::kNegX}, .kind = JointKind::kVertical});
}

// A dowel meeting across the bed joint between lower block lo and upper block up when
// they overlap enough; the joint itself whenever they overlap.
void add_bed_joint(const Draws& draws, int lo, int up, Monument& m) {
    const MonumentBlock& L = m.blocks[lo];
    const MonumentBlock& U = m.blocks[up];
    const double xl = L.T_monument_block.translation().x(), hl = 0.5 * L.config.size_m.x();
    const double xu = U.T_monument_block.translation().x(), hu = 0.5 * U.config.size_m.x();
    const double x0 = std::max(xl - hl, xu - hu), x1 = std::min(xl + hl, xu + hu);
    if (x1 - x0 < 0.05) return;
    m.joints.push_back(
        {.a = {lo, BlockFace::kPosZ}, .b = {up, BlockFace::kNegZ}, .kind = JointKind::kBed});
    if (x1 - x0 < 0.3) return;
    const double x = draws.uniform(60, lo * 1000 + up, x0 + 0.12, x1 - 0.12);
    const double y = draws.uniform(61, lo * 1000 + up, -0.2, 0.2) * L.config.size_m.y();
    const double radius_m = draws.uniform(62, lo * 1000 + up, 0.015, 0.025);
    const double depth_m = draws.uniform(63, lo * 1000 + up, 0.04, 0.06);
    // Top face axes (a, b) = (+x, +y); bottom face axes (a, b) = (+y, +x).
    m.blocks[lo].config.dowel_holes.push_back({.face = BlockFace::kPosZ,
                                               .u_m = x - xl,
                                               .v_m = y,
                                               .radius_m = radius_m,
                                               .depth_m = depth_m});
    m.blocks[up].config.dowel_holes.push_back({.face = BlockFace::kNegZ,
                                               .u_m = y,
                                               .v_m = x - xu,
                                               .radius_m = radius_m,
                                               .depth_m = depth_m});
}

void weather_and_lay_down(const MonumentConfig& c, const Draws& draws, Monument& m) {
    const WeatheringConfig& w = c.weathering;
    const int columns = static_cast<int>(std::ceil(std::sqrt(double(m.blocks.size()))));
    for (std::size_t i = 0; i < m.blocks.size(); ++i) {
        StoneBlockConfig& b = m.blocks[i].config;
        b.chip_count = static_cast<int>(draws.uniform(70, i, 0.0, w.max_chips + 0.999));
        b.chip_max_depth_m = w.chip_max_depth_m;
        b.lost_corner_count = draws.uniform(71, i, 0.0, 1.0) < w.lost_corner_share ? 1 : 0;
        b.lost_corner_max_depth_m = w.lost_corner_depth_m;
        b.erosion_m = w.erosion_m;
        const BlockPlacement placement{
            .resting_face =
                static_cast<BlockFace>(static_cast<int>(draws.uniform(72, i, 0.0, 5.999))),
            .yaw_deg = draws.uniform(73, i, 0.0, 360.0),
            .position_m = c.ground_spacing_m *
                          Eigen::Vector2d(double(int(i) % columns), double(int(i) / columns))};
        m.blocks[i].T_ground_block = block_pose(placement, b.size_m);
    }
}

}  // namespace

Expected<Monument> make_monument(const MonumentConfig& c) {
    if (c.courses < 1 || c.blocks_per_course < 1 || c.depth_m <= 0.0)
        return fail(ErrorCode::kInvalidArgument,
                    "monument " + c.name + ": needs at least one course and block");
    const Draws draws{c.seed};
    Monument m{.name = c.name};
    std::vector<double> joints_below;
    std::vector<std::vector<int>> course_blocks(static_cast<std::size_t>(c.courses));
    double z = 0.0;
    for (int course = 0; course < c.courses; ++course) {
        auto lengths = course_lengths(c, draws, course, joints_below);
        if (!lengths) return Unexpected(lengths.error());
        const double height_m =
            draws.uniform(20, course, c.min_course_height_m, c.max_course_height_m);
        joints_below.clear();
        double x = 0.0;
        for (std::size_t i = 0; i < lengths->size(); ++i) {
            course_blocks[course].push_back(static_cast<int>(m.blocks.size()));
            m.blocks.push_back(make_block(c, draws, course, static_cast<int>(i),
                                          {x, -0.5 * c.depth_m, z},
                                          {(*lengths)[i], c.depth_m, height_m}));
            x += (*lengths)[i];
            joints_below.push_back(x);
        }
        z += height_m;
    }
    add_facade_lines(c, m);
    for (const std::vector<int>& row : course_blocks)
        for (std::size_t i = 0; i + 1 < row.size(); ++i)
            add_vertical_joint(draws, row[i], row[i + 1], m);
    for (std::size_t course = 0; course + 1 < course_blocks.size(); ++course)
        for (int lo : course_blocks[course])
            for (int up : course_blocks[course + 1]) add_bed_joint(draws, lo, up, m);
    weather_and_lay_down(c, draws, m);
    return m;
}

Mesh block_mesh(const MonumentBlock& block) { return make_stone_block(block.config); }

Mesh transformed_mesh(const Mesh& mesh_block, const Pose& T_to_block) {
    Mesh out = mesh_block;
    const Eigen::Matrix3f R = T_to_block.linear().cast<float>();
    const Eigen::Vector3f t = T_to_block.translation().cast<float>();
    for (Eigen::Vector3f& p : out.vertices.positions) p = R * p + t;
    for (Eigen::Vector3f& n : out.vertices.normals) n = R * n;
    return out;
}

std::string_view face_name(BlockFace face) {
    static constexpr std::string_view kNames[kBlockFaceCount] = {"+x", "-x", "+y",
                                                                 "-y", "+z", "-z"};
    return kNames[static_cast<int>(face)];
}

std::vector<MonumentInfo> monument_catalog() {
    return {{"octagon-base-course", "one course of 6 blocks with the ornament band and moulding"},
            {"octagon-wall", "two courses of 7 blocks (14), band below, moulding on top"},
            {"octagon-wall-3", "three courses of 5 blocks (15)"}};
}

Expected<MonumentConfig> named_monument(std::string_view name, std::uint64_t seed) {
    MonumentConfig c{.name = std::string(name)};
    if (name == "octagon-base-course") {
        c.courses = 1;
        c.blocks_per_course = 6;
        c.seed = 11;
    } else if (name == "octagon-wall") {
        c.courses = 2;
        c.blocks_per_course = 7;
        c.seed = 21;
    } else if (name == "octagon-wall-3") {
        c.courses = 3;
        c.blocks_per_course = 5;
        c.seed = 31;
    } else {
        return fail(ErrorCode::kInvalidArgument,
                    "unknown monument section '" + std::string(name) +
                        "' (known: octagon-base-course, octagon-wall, octagon-wall-3)");
    }
    if (seed != 0) c.seed = seed;
    return c;
}

}  // namespace anascan::sim
