#include "anascan/sim/sim_world.hpp"

#include <cstdio>

namespace anascan::sim {
namespace {

/// Everything of a scene config that changes its mesh (a predefined scene's name fixes
/// the rest of the block).
std::string world_key(const SceneConfig& c) {
    char key[256];
    std::snprintf(key, sizeof(key), "%s|%.6f|%llu|%d|%.6f|%.6f|%.6f|%d", c.name.c_str(),
                  c.block.grid_step_m, static_cast<unsigned long long>(c.block.seed),
                  static_cast<int>(c.placement.resting_face), c.placement.yaw_deg,
                  c.placement.position_m.x(), c.placement.position_m.y(), c.with_tent ? 1 : 0);
    return key;
}

}  // namespace

Expected<std::shared_ptr<const SimWorld>> make_sim_world(const SceneConfig& config) {
    Scene scene = make_scene(config);
    auto caster = RayCaster::create(scene.mesh);
    if (!caster) return fail(caster.error());
    std::vector<float> albedos = triangle_albedos(scene);
    return std::make_shared<const SimWorld>(
        SimWorld{std::move(scene), std::move(*caster), std::move(albedos)});
}

Expected<std::shared_ptr<const SimWorld>> SimWorldCache::get(const SceneConfig& config) {
    const std::string key = world_key(config);
    std::lock_guard lock(mutex_);
    if (auto world = worlds_[key].lock()) return world;
    auto world = make_sim_world(config);
    if (world) worlds_[key] = *world;
    return world;
}

}  // namespace anascan::sim
