#pragma once
/// \file
/// What a simulated device looks at: a scene with its ray caster and albedos, built once
/// and shared by the devices that view it.

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/sim/ray_caster.hpp"
#include "anascan/sim/scene.hpp"

namespace anascan::sim {

/// A scene ready for ray casting. Immutable after creation, so thread-safe to share.
struct SimWorld {
    Scene scene;
    RayCaster caster;
    std::vector<float> albedos;  ///< Per triangle of scene.mesh.
};

/// Builds the scene of `config` and its BVH.
Expected<std::shared_ptr<const SimWorld>> make_sim_world(const SceneConfig& config);

/// Worlds by scene config, so that opening a device twice does not rebuild its scene.
/// Holds weak references: a world lives while a device uses it. Thread-safe.
class SimWorldCache {
public:
    Expected<std::shared_ptr<const SimWorld>> get(const SceneConfig& config);

private:
    std::mutex mutex_;
    std::map<std::string, std::weak_ptr<const SimWorld>> worlds_;
};

}  // namespace anascan::sim
