#pragma once
// Small scenes shared by the simulator tests (coarse meshes keep the suite fast).

#include "anascan/sim/ray_caster.hpp"
#include "anascan/sim/scene.hpp"

namespace anascan::sim::testing {

/// The small block of the catalogue with a mesh spacing of `step_m`.
inline Scene small_scene(double step_m = 0.004) {
    SceneConfig config = named_scene("small-block").value();
    config.block.grid_step_m = step_m;
    return make_scene(config);
}

inline RayCaster caster_of(const Mesh& mesh) { return RayCaster::create(mesh).value(); }

}  // namespace anascan::sim::testing
