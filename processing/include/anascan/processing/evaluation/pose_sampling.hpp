#pragma once
/// \file
/// Random rigid poses for simulations, tests and accuracy checks (seeded, reproducible).

#include <random>

#include "anascan/processing/core/pose.hpp"

namespace anascan {

/// A rotation uniform over SO(3) (normalised Gaussian quaternion) and a translation in a
/// uniformly random direction with a length uniform in [0, max_translation_m].
Pose sample_random_pose(std::mt19937& rng, double max_translation_m);

}  // namespace anascan
