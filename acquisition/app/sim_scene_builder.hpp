#pragma once
// Builds a named simulation scene for the `sim` commands (fails the command on an unknown
// name); step_mm > 0 and seed >= 0 override the scene's block mesh spacing and seed.

#include <string>

#include "anascan/sim/scene.hpp"

namespace anascan::cli {

sim::Scene build_named_scene(const std::string& name, double step_mm, long long seed);

}  // namespace anascan::cli
