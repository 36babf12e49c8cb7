// Picking in the 3D view: a world point projected into the view and the ray back through
// that place meet again; a click lands on the nearest point in front of the eye within its
// reach, in the points' own frame; nothing behind the eye or off the ray is hit.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "anascan/gui/view_picking.hpp"

namespace anascan::gui {
namespace {

OrbitCamera camera_on(const Eigen::Vector3d& centre) {
    OrbitCamera camera;
    camera.fit({.centre_m = centre, .radius_m = 0.5}, 1.5);
    camera.orbit(40.0, -25.0);
    return camera;
}

TEST(ViewPicking, AProjectedPointLiesOnTheRayThroughItsPlace) {
    const OrbitCamera camera = camera_on({1000.0, 2000.0, 5.0});  // site coordinates
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d(1000.2, 2000.1, 5.3), Eigen::Vector3d(999.7, 1999.8, 4.9)}) {
        const auto ndc = project_to_view(camera, 1.5, p);
        ASSERT_TRUE(ndc);
        EXPECT_LT(ndc->cwiseAbs().maxCoeff(), 1.0);
        const ViewRay ray = view_ray(camera, 1.5, *ndc);
        const Eigen::Vector3d v = p - ray.origin_m;
        EXPECT_LT((v - v.dot(ray.direction) * ray.direction).norm(), 1e-9);
        EXPECT_NEAR(ray.direction.norm(), 1.0, 1e-12);
    }
    // Behind the eye: nowhere in the view.
    const Eigen::Vector3d behind = camera.eye_m() + (camera.eye_m() - camera.target_m());
    EXPECT_FALSE(project_to_view(camera, 1.5, behind));
}

TEST(ViewPicking, TheNearestPointWithinReachIsHitInThePointsFrame) {
    const OrbitCamera camera = camera_on(Eigen::Vector3d::Zero());
    const Eigen::Vector3d eye = camera.eye_m(), towards = (camera.target_m() - eye).normalized();
    // Three points on the line of sight (in the world), placed by a pose, and one beside it.
    const Eigen::Isometry3d T(Eigen::Translation3d(0.3, -0.2, 0.1) *
                              Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
    auto local = [&](const Eigen::Vector3d& world) -> Eigen::Vector3f {
        return (T.inverse() * world).cast<float>();
    };
    const double d = camera.distance_m();
    const std::vector<Eigen::Vector3f> points{
        local(eye + 1.2 * d * towards), local(eye + 0.8 * d * towards),
        local(eye + 0.5 * d * towards + 0.05 * d * towards.cross(Eigen::Vector3d::UnitZ())),
        local(eye - 0.5 * d * towards)};
    const auto ndc = project_to_view(camera, 1.0, camera.target_m());
    ASSERT_TRUE(ndc);
    const ViewRay ray = view_ray(camera, 1.0, *ndc);
    const auto hit = pick_point(points, T, ray, 0.01);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->index, 1u);  // not the one beside the ray, not the one behind the eye
    EXPECT_NEAR(hit->depth_m, 0.8 * d, 1e-6 * d);
    // With a reach wide enough the point beside the ray, nearer the eye, is hit.
    EXPECT_EQ(pick_point(points, T, ray, 0.2)->index, 2u);
    EXPECT_FALSE(pick_point(std::span(points).first(0), T, ray, 0.2));
}

}  // namespace
}  // namespace anascan::gui
