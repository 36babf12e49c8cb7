// Surface roughness (paper §5.1, after Huang et al. 2006): the local bending energy
//   e_k(p) = 1/k Σ_i ||n_p - n_qi||² / ||p - q_i||²   over the k nearest neighbours q_i,
//   ρ(p) = mean of e_k(q) over the ball N_r(p),
// and ρ(F) the median (the paper: mean) of ρ(p) over evenly spread samples p of the face:
// a façade's ornament band or moulding is carving, not its finish, and the median keeps
// it out as long as it covers less than half the face.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "feature_steps.hpp"

namespace anascan::reassembly::detail {
namespace {

double bending_energy(const FeatureInput& in, std::size_t p, int k, std::vector<Neighbor>& nn) {
    in.tree.knn(in.points[p], static_cast<std::size_t>(k) + 1, nn);
    double sum = 0.0;
    int count = 0;
    for (const Neighbor& q : nn) {
        if (q.index == p || q.distance_sq_m2 <= 0.0f) continue;
        sum += double((in.normals[p] - in.normals[q.index]).squaredNorm()) / q.distance_sq_m2;
        ++count;
    }
    return count > 0 ? sum / count : 0.0;
}

double roughness_of(const FeatureInput& in, const std::vector<int>& point_face, const FaceBuild& f,
                    const RoughnessConfig& c) {
    const std::size_t stride =
        std::max<std::size_t>(1, f.inliers.size() / std::size_t(std::max(1, c.samples_per_face)));
    const float radius_m = static_cast<float>(c.radius_factor * std::max(in.spacing_m, 1e-6));
    std::vector<Neighbor> ball, nn;
    std::vector<double> rho;
    for (std::size_t s = 0; s < f.inliers.size(); s += stride) {
        in.tree.radius_any_order(in.points[f.inliers[s]], radius_m, ball);
        double ball_sum = 0.0;
        int ball_count = 0;
        for (const Neighbor& q : ball) {
            if (point_face[q.index] != f.face.id) continue;  // The ball within the face.
            ball_sum += bending_energy(in, q.index, c.k_neighbors, nn);
            ++ball_count;
        }
        if (ball_count == 0) continue;
        rho.push_back(ball_sum / ball_count);
    }
    if (rho.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::nth_element(rho.begin(), rho.begin() + std::ptrdiff_t(rho.size() / 2), rho.end());
    return rho[rho.size() / 2];
}

}  // namespace

void face_roughness(const FeatureInput& in, const std::vector<int>& point_face,
                    std::vector<FaceBuild>& faces, const RoughnessConfig& c) {
    tbb::parallel_for(std::size_t{0}, faces.size(), [&](std::size_t i) {
        faces[i].face.roughness_per_m2 = roughness_of(in, point_face, faces[i], c);
    });
}

}  // namespace anascan::reassembly::detail
