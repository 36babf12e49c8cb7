#pragma once
// Small scenes shared by the simulator tests (coarse meshes keep the suite fast).

#include <gtest/gtest.h>

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

/// A test suite sharing one small block scene (2 mm mesh) and its ray caster.
class SmallSceneSuite : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        scene_ = new Scene(small_scene(0.002));
        caster_ = new RayCaster(caster_of(scene_->mesh));
    }
    static void TearDownTestSuite() {
        delete caster_;
        delete scene_;
    }

    static inline Scene* scene_ = nullptr;
    static inline RayCaster* caster_ = nullptr;
};

}  // namespace anascan::sim::testing
