#pragma once
// A session store of four overlapping strips of one relief, each registered as a test says:
// real scans of a surface that registers (not a plane, so not ground), on a real store.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <memory>

#include "../processing/test_bumpy_surface.hpp"
#include "anascan/acquisition/store/session_store.hpp"

namespace anascan::testing_util {

/// Four overlapping strips (8 cm long, 4 cm apart) of one relief on a curved base, saved into
/// a new session store at `dir`, strip k (0-3) recorded with the registration `update(k)`.
inline std::unique_ptr<acquisition::SessionStore> session_of_strips(
    const std::filesystem::path& dir,
    const std::function<acquisition::RegistrationUpdate(int)>& update) {
    auto store = acquisition::SessionStore::open(dir, acquisition::SessionOpenMode::kCreateOrOpen);
    EXPECT_TRUE(store.has_value());
    if (!store) return nullptr;
    const auto bumps = random_bumps(11, 40);
    for (int k = 0; k < 4; ++k) {
        const double x0 = -0.1 + 0.04 * k;
        Scan scan;
        scan.meta.device_id = "sim:test#0";
        scan.meta.sensor_origin_scan_m = Eigen::Vector3d(x0 + 0.04, 0.0, 0.5);
        scan.cloud = bumpy_surface(bumps, x0, x0 + 0.08, 0.001, 0.0003 * k);
        for (Eigen::Vector3f& p : scan.cloud.positions)  // Not a plane: not the ground.
            p.z() += 10.0f * (p.x() * p.x() + p.y() * p.y());
        auto saved = (*store)->save_scan(scan, std::nullopt);
        EXPECT_TRUE(saved.has_value());
        if (saved) {
            EXPECT_TRUE((*store)->record_registration(saved->seq, update(k)).has_value());
        }
    }
    return std::move(*store);
}

}  // namespace anascan::testing_util
