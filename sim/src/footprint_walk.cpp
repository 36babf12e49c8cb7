#include "anascan/sim/footprint_walk.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace anascan::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector2d turned_left(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }

/// One piece of the walk: a face (the aim slides from `from` to `to`, outward fixed) or a
/// corner (the aim stays, outward turns from `from_dir` by +90°).
struct Piece {
    bool corner = false;
    Eigen::Vector2d from = Eigen::Vector2d::Zero();
    Eigen::Vector2d to = Eigen::Vector2d::Zero();
    Eigen::Vector2d from_dir = Eigen::Vector2d::UnitX();
    double steps = 0.0;
};

std::array<Piece, 9> walk_pieces(const Footprint& f, const WalkSpacing& s) {
    const Eigen::Vector2d u = f.axis_u, v = turned_left(f.axis_u);
    const Eigen::Vector2d c = f.centre_m;
    const double hu = f.half_u_m, hv = f.half_v_m;
    const double corner_steps = 90.0 / s.corner_step_deg;
    auto face = [&](Eigen::Vector2d a, Eigen::Vector2d b, Eigen::Vector2d out) {
        return Piece{.from = a, .to = b, .from_dir = out, .steps = (b - a).norm() / s.face_step_m};
    };
    auto corner = [&](Eigen::Vector2d at, Eigen::Vector2d out) {
        return Piece{.corner = true, .from = at, .to = at, .from_dir = out, .steps = corner_steps};
    };
    const Eigen::Vector2d pp = c + hu * u + hv * v, mp = c - hu * u + hv * v;
    const Eigen::Vector2d mm = c - hu * u - hv * v, pm = c + hu * u - hv * v;
    return {face(c + hu * u, pp, u), corner(pp, u),    face(pp, mp, v),
            corner(mp, v),           face(mp, mm, -u), corner(mm, -u),
            face(mm, pm, -v),        corner(pm, -v),   face(pm, c + hu * u, u)};
}

}  // namespace

Footprint block_footprint(const BlockPlacement& placement, const Eigen::Vector3d& size_m) {
    const Pose T = block_pose(placement, size_m);
    const Eigen::Matrix3d& R = T.linear();
    // The block rests on a face: one of its axes is vertical, the other two horizontal.
    int vertical = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(R(2, k)) > std::abs(R(2, vertical))) vertical = k;
    const int a = (vertical + 1) % 3, b = (vertical + 2) % 3;
    Footprint f;
    f.centre_m = T.translation().head<2>();
    f.axis_u = R.col(a).head<2>().normalized();
    f.half_u_m = 0.5 * std::abs(size_m[a]);
    f.half_v_m = 0.5 * std::abs(size_m[b]);
    const double half_height = 0.5 * std::abs(size_m[vertical]);
    f.bottom_m = T.translation().z() - half_height;
    f.top_m = T.translation().z() + half_height;
    return f;
}

WalkSpacing walk_spacing(double distance_m, double field_width_deg, double overlap,
                         double corner_step_deg) {
    const double field_m = 2.0 * distance_m * std::tan(0.5 * field_width_deg * kPi / 180.0);
    return {.face_step_m = std::max(1e-3, (1.0 - std::clamp(overlap, 0.0, 0.95)) * field_m),
            .corner_step_deg = std::max(1.0, corner_step_deg)};
}

int walk_views(const Footprint& footprint, const WalkSpacing& spacing) {
    double steps = 0.0;
    for (const Piece& piece : walk_pieces(footprint, spacing)) steps += piece.steps;
    return std::max(1, static_cast<int>(std::ceil(steps - 1e-9)));
}

OutlinePoint outline_point(const Footprint& footprint, const WalkSpacing& spacing,
                           double fraction) {
    const std::array<Piece, 9> pieces = walk_pieces(footprint, spacing);
    double total = 0.0;
    for (const Piece& piece : pieces) total += piece.steps;
    double at = (fraction - std::floor(fraction)) * total;
    for (const Piece& piece : pieces) {
        if (at > piece.steps && &piece != &pieces.back()) {
            at -= piece.steps;
            continue;
        }
        const double t = piece.steps > 0.0 ? std::clamp(at / piece.steps, 0.0, 1.0) : 0.0;
        if (!piece.corner) return {piece.from + t * (piece.to - piece.from), piece.from_dir};
        const double angle = 0.5 * kPi * t;
        return {piece.from,
                std::cos(angle) * piece.from_dir + std::sin(angle) * turned_left(piece.from_dir)};
    }
    return {};
}

}  // namespace anascan::sim
