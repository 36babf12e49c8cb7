#include "stone_relief.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hash_random.hpp"

namespace anascan::sim::detail {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

double smoothstep(double x) {
    const double t = std::clamp(x, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Depth of a pocket with near-vertical walls (one wall_m wide) given the signed distance
// of the point inside its outline (positive inside).
double pocket_m(double inside_m, double depth_m, double wall_m) {
    return depth_m * std::clamp(inside_m / wall_m + 0.5, 0.0, 1.0);
}

// Signed distance inside the rectangle |s - s_c| <= hs, |w| <= hw (positive inside).
double inside_rect(double s, double w, double s_c, double hs, double hw) {
    return std::min(hs - std::abs(s - s_c), hw - std::abs(w));
}

// Tool marks of a face finish, in [0, amplitude]: random pits (pointed) or parallel
// claw-chisel grooves with a wavering course.
double finish_m(const FaceFinish& f, std::uint64_t seed, double u, double v) {
    const double x = u / f.wavelength_m, y = v / f.wavelength_m;
    if (!f.parallel_grooves) return f.amplitude_m * fractal_noise(seed, x, y, 3);
    const double angle = f.groove_angle_deg * kDegToRad;
    const double across = -std::sin(angle) * x + std::cos(angle) * y;
    const double waver = 0.3 * (value_noise(seed + 7, 0.2 * x, 0.2 * y) - 0.5);
    const double groove = 0.5 + 0.5 * std::cos(2.0 * std::numbers::pi * (across + waver));
    return f.amplitude_m * (0.75 * groove + 0.25 * fractal_noise(seed, 2 * x, 2 * y, 2));
}

double clamp_hole_m(const StoneBlockConfig& config, const FaceFrame& top, const ClampHole& hole,
                    double u, double v) {
    const Eigen::Vector3d n_edge = face_normal(hole.edge_face);
    const double ea = n_edge.dot(top.a), eb = n_edge.dot(top.b);
    if (std::abs(ea) + std::abs(eb) < 0.5) return 0.0;  // Not a side face of the top.
    const double edge_m = std::abs(ea) * top.half_a_m + std::abs(eb) * top.half_b_m;
    const double s = ea * u + eb * v;                   // Toward the edge.
    const double w = -eb * u + ea * v - hole.offset_m;  // Along the edge.
    const double end_m = hole.open_at_edge ? edge_m + hole.width_m : edge_m - 0.5 * config.margin_m;
    const double start_m = end_m - hole.length_m;
    const double hw = 0.5 * hole.width_m, wall = config.grid_step_m;
    const double channel =
        pocket_m(inside_rect(s, w, 0.5 * (start_m + end_m), 0.5 * hole.length_m, hw),
                 hole.channel_depth_m, wall);
    const double pocket_a =
        pocket_m(inside_rect(s, w, start_m + hw, hw, hw), hole.pocket_depth_m, wall);
    const double pocket_b =
        pocket_m(inside_rect(s, w, end_m - hw, hw, hw), hole.pocket_depth_m, wall);
    return std::max({channel, pocket_a, pocket_b});
}

// Egg-and-dart band: carved background with ellipsoidal eggs standing to the surface.
double ornament_m(const StoneBlockConfig& config, const FaceFrame& frame, double u, double v) {
    const OrnamentBand& band = config.ornament;
    if (!band.enabled || band.face != frame.face || std::abs(frame.n.z()) > 0.5) return 0.0;
    // In side faces one axis is vertical (z); the other runs along the band.
    const bool a_vertical = std::abs(frame.a.z()) > 0.5;
    const double z = a_vertical ? u * frame.a.z() : v * frame.b.z();
    const double along = a_vertical ? v : u;
    const double half_along = (a_vertical ? frame.half_b_m : frame.half_a_m) -
                              (band.run_to_edges ? 0.0 : config.margin_m);
    const double half_z = std::abs(a_vertical ? frame.half_a_m : frame.half_b_m);
    const double z_mid = half_z - band.top_offset_m - 0.5 * band.height_m;
    const double inside = inside_rect(z, along, z_mid, 0.5 * band.height_m, half_along);
    if (inside <= -config.grid_step_m) return 0.0;
    const double shifted = (along + band.phase_m) / band.period_m;
    const double phase = shifted - std::floor(shifted) - 0.5;
    const double dz = (z - z_mid) / (0.4 * band.height_m);
    const double r2 = (phase / 0.38) * (phase / 0.38) + dz * dz;
    const double egg = r2 < 1.0 ? std::sqrt(1.0 - r2) : 0.0;
    return pocket_m(inside, band.depth_m * (1.0 - egg), config.grid_step_m);
}

// Cavetto moulding: depth below the face as a function of the height in the face only.
double moulding_m(const Moulding& m, const FaceFrame& frame, double u, double v) {
    if (!m.enabled || m.face != frame.face || std::abs(frame.n.z()) > 0.5) return 0.0;
    const bool a_vertical = std::abs(frame.a.z()) > 0.5;
    const double z = a_vertical ? u * frame.a.z() : v * frame.b.z();
    const double half_z = a_vertical ? frame.half_a_m : frame.half_b_m;
    const double below_top = half_z - z - m.top_offset_m;  // Down from the fillet.
    if (below_top <= 0.0 || below_top >= m.height_m) return 0.0;
    const double t = below_top / m.height_m;  // 0 at the fillet, 1 at the foot.
    return m.depth_m * std::sqrt(std::max(0.0, 1.0 - (2.0 * t - 1.0) * (2.0 * t - 1.0)));
}

}  // namespace

FaceFrame face_frame(BlockFace face, const Eigen::Vector3d& half_m) {
    // Normal axis, first and second in-face axes (a x b = n), as signed axis indices + 1.
    static constexpr int kAxes[kBlockFaceCount][3] = {{1, 2, 3},  {-1, 3, 2}, {2, 3, 1},
                                                      {-2, 1, 3}, {3, 1, 2},  {-3, 2, 1}};
    auto axis = [](int signed_index) {
        return static_cast<double>(signed_index > 0 ? 1 : -1) *
               Eigen::Vector3d::Unit(std::abs(signed_index) - 1);
    };
    const int* axes = kAxes[static_cast<int>(face)];
    FaceFrame f{.face = face, .n = axis(axes[0]), .a = axis(axes[1]), .b = axis(axes[2])};
    f.half_a_m = f.a.cwiseAbs().dot(half_m);
    f.half_b_m = f.b.cwiseAbs().dot(half_m);
    f.half_n_m = f.n.cwiseAbs().dot(half_m);
    return f;
}

double face_relief_m(const StoneBlockConfig& config, const FaceFrame& frame, double u, double v) {
    const auto face_index = static_cast<std::uint64_t>(frame.face);
    const double edge_distance_m =
        std::min(frame.half_a_m - std::abs(u), frame.half_b_m - std::abs(v));
    const double fade = smoothstep(edge_distance_m / std::max(config.margin_m, 1e-9));
    const FaceFinish& finish = config.finishes[face_index];
    double depth_m =
        fade * (finish.recess_m + finish_m(finish, hash3(config.seed, 101, face_index), u, v));
    depth_m = std::max(depth_m, ornament_m(config, frame, u, v));
    depth_m = std::max(depth_m, moulding_m(config.moulding, frame, u, v));
    if (config.erosion_m > 0.0)
        depth_m += config.erosion_m *
                   fractal_noise(hash3(config.seed, 202, face_index), u / 0.04, v / 0.04, 3);
    if (frame.face == BlockFace::kPosZ) {
        for (const ClampHole& hole : config.clamp_holes)
            depth_m = std::max(depth_m, clamp_hole_m(config, frame, hole, u, v));
    }
    for (const DowelHole& hole : config.dowel_holes) {
        if (hole.face != frame.face) continue;
        const double r = std::hypot(u - hole.u_m, v - hole.v_m);
        depth_m = std::max(depth_m, pocket_m(hole.radius_m - r, hole.depth_m, config.grid_step_m));
    }
    // Never cut through the block.
    return std::min(depth_m, 0.8 * frame.half_n_m);
}

}  // namespace anascan::sim::detail
