#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>

#include "anascan/processing/spatial/triangle_tree.hpp"
#include "anascan/processing/surface/model_report.hpp"
#include "anascan/processing/surface/truth_comparison.hpp"
#include "surface_test_meshes.hpp"

namespace anascan {
namespace {

using test::grid_box;

// Coarse samples: the figures here do not need the default 0.2 / 0.5 mm ones.
const TruthComparisonConfig kCoarse{.model_spacing_m = 2e-3, .truth_spacing_m = 3e-3};

Mesh moved(Mesh m, const Pose& T) {
    m.vertices = transformed(m.vertices, T);
    return m;
}

TEST(TriangleTree, ClosestPointAndSegmentHitsOnABox) {
    const Mesh box = grid_box({0.4, 0.3, 0.2}, 4);
    const TriangleTree tree(box.vertices.positions, box.triangles);
    EXPECT_EQ(tree.size(), box.triangles.size());
    Eigen::Vector3d q;
    std::size_t t = 0;
    ASSERT_TRUE(tree.closest({0.0, 0.0, 0.5}, q, t));
    EXPECT_NEAR(q.z(), 0.1, 1e-7);
    EXPECT_TRUE(tree.segment_hits({0.0, 0.0, 0.5}, {0.0, 0.0, 0.0}));   // into the box
    EXPECT_FALSE(tree.segment_hits({0.0, 0.0, 0.5}, {0.5, 0.0, 0.5}));  // above it
    const TriangleTree empty({}, {});
    EXPECT_FALSE(empty.closest({0, 0, 0}, q, t));
    EXPECT_FALSE(empty.segment_hits({0, 0, 0}, {1, 1, 1}));
}

TEST(OrientedBox, ARotatedBoxGivesItsEdgesWhateverItsPose) {
    const Mesh box = grid_box({0.45, 0.40, 0.35}, 6);
    for (const double angle_deg : {3.0, 20.0, 45.0}) {
        const Pose T(Eigen::AngleAxisd(angle_deg * std::numbers::pi / 180.0,
                                       Eigen::Vector3d(0.3, 0.2, 1.0).normalized()));
        const Eigen::Vector3d obb = oriented_box_mm(moved(box, T));
        EXPECT_NEAR(obb.x(), 450.0, 0.5) << angle_deg;
        EXPECT_NEAR(obb.y(), 400.0, 0.5) << angle_deg;
        EXPECT_NEAR(obb.z(), 350.0, 0.5) << angle_deg;
    }
}

TEST(TruthComparison, AnOffsetSurfaceIsMeasuredAtItsOffset) {
    const Mesh truth = grid_box({0.4, 0.3, 0.2}, 8);
    const Mesh model = grid_box({0.402, 0.302, 0.202}, 5);  // 1 mm outside every face
    const TruthComparison c = compare_with_truth(model, {}, truth, kCoarse);
    EXPECT_GT(c.measured_samples, 50000u);
    EXPECT_EQ(c.interpolated_samples, 0u);
    EXPECT_NEAR(c.measured_median_m, 1e-3, 1e-5);
    EXPECT_GT(c.measured_max_m, 1.2e-3);  // near the corners: up to sqrt(3) mm
    EXPECT_LT(c.measured_max_m, std::sqrt(3.0) * 1e-3 + 1e-6);
    EXPECT_LT(c.completeness, 0.01);  // 1 mm away everywhere: nothing within 0.5 mm
    const TruthComparison self = compare_with_truth(truth, {}, truth, kCoarse);
    EXPECT_LT(self.measured_p95_m, 1e-6);
    EXPECT_DOUBLE_EQ(self.completeness, 1.0);
    EXPECT_NEAR(self.truth_box_m.x(), 0.4, 1e-6);
}

TEST(TruthComparison, InterpolatedTrianglesAreLeftOutOfTheMeasuredAccuracy) {
    const Mesh truth = grid_box({0.4, 0.3, 0.2}, 8);
    Mesh model = truth;
    std::vector<SurfaceClass> classes(model.triangles.size(), SurfaceClass::kMeasured);
    for (std::size_t t = 0; t < model.triangles.size(); ++t) {
        const auto& p = model.vertices.positions;
        const Eigen::Vector3i& f = model.triangles[t];
        if (p[f[0]].z() > 0.099f && p[f[1]].z() > 0.099f && p[f[2]].z() > 0.099f) {
            classes[t] = SurfaceClass::kInterpolated;  // the top face, moved up by 5 mm
            for (int k = 0; k < 3; ++k) model.vertices.positions[f[k]].z() = 0.105f;
        }
    }
    const TruthComparison c = compare_with_truth(model, classes, truth, kCoarse);
    EXPECT_LT(c.measured_p95_m, 1e-6);
    EXPECT_NEAR(c.interpolated_median_m, 5e-3, 1e-4);
}

TEST(TruthVisibility, TheBottomOfABoxSeenFromAboveIsTheUnseenPart) {
    const Mesh truth = grid_box({0.4, 0.3, 0.2}, 10);
    // Four sensors 1 m away around and above, looking at the centre.
    std::vector<Pose> views;
    for (int k = 0; k < 4; ++k) {
        const double a = k * std::numbers::pi / 2.0;
        const Eigen::Vector3d eye(std::cos(a), std::sin(a), 0.8);
        const Eigen::Vector3d z = -eye.normalized(),
                              x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
        Pose T = Pose::Identity();
        T.linear() << x, z.cross(x), z;
        T.translation() = eye;
        views.push_back(T);
    }
    // The model: the truth with its bottom classed interpolated.
    std::vector<SurfaceClass> classes(truth.triangles.size(), SurfaceClass::kMeasured);
    for (std::size_t t = 0; t < truth.triangles.size(); ++t)
        if (truth.vertices.positions[truth.triangles[t][0]].z() < -0.099f &&
            truth.vertices.positions[truth.triangles[t][1]].z() < -0.099f &&
            truth.vertices.positions[truth.triangles[t][2]].z() < -0.099f)
            classes[t] = SurfaceClass::kInterpolated;
    const VisibilityConfig config{.sample_spacing_m = 4e-3};
    const VisibilityAgreement a =
        compare_classes_with_visibility(truth, classes, truth, views, config);
    EXPECT_NEAR(a.unseen_area_m2, 0.4 * 0.3, 0.01);  // the bottom, and nothing else
    EXPECT_GT(a.unseen_interpolated_share(), 0.95);
    EXPECT_LT(a.seen_interpolated_share(), 0.02);
    EXPECT_NEAR(a.seen_covered_m2, a.seen_area_m2, 1e-9);  // the model is the truth
    EXPECT_NEAR(a.unseen_covered_m2, a.unseen_area_m2, 1e-9);
    // A narrow field of view sees only the middle of each side: more is unseen.
    const VisibilityConfig narrow{
        .sample_spacing_m = 4e-3,
        .devices = {{.horizontal_fov_deg = 5.0, .vertical_fov_deg = 5.0}}};
    const VisibilityAgreement b =
        compare_classes_with_visibility(truth, classes, truth, views, narrow);
    EXPECT_GT(b.unseen_area_m2, a.unseen_area_m2 + 0.1);
}

// A 0.4 x 0.3 x 0.2 m box and a 60-degree camera 1 m above its top, looking down.
struct TopView {
    Mesh truth = grid_box({0.4, 0.3, 0.2}, 10);
    std::vector<SurfaceClass> classes =
        std::vector<SurfaceClass>(truth.triangles.size(), SurfaceClass::kMeasured);
    VisibilityDevice camera{.horizontal_fov_deg = 60.0, .vertical_fov_deg = 60.0};
    Pose T_world_view = looking_down_from(0.0);

    static Pose looking_down_from(double x_m) {
        Pose T = Pose::Identity();  // +z of the view is -z
        T.linear() = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).matrix();
        T.translation() = Eigen::Vector3d(x_m, 0.0, 1.1);
        return T;
    }
    VisibilityAgreement seen_by(std::vector<VisibilityDevice> devices, const Pose& T,
                                double seen_deg = 70.0, double unseen_deg = 80.0) const {
        const VisibilityConfig config{.seen_incidence_deg = seen_deg,
                                      .unseen_incidence_deg = unseen_deg,
                                      .sample_spacing_m = 4e-3,
                                      .devices = std::move(devices)};
        return compare_classes_with_visibility(truth, classes, truth, std::vector<Pose>{T}, config);
    }
};

TEST(TruthVisibility, ASampleIsSeenOnlyWhereEveryDeviceOfTheSensorSeesIt) {
    const TopView v;
    const VisibilityAgreement a = v.seen_by({v.camera}, v.T_world_view);
    EXPECT_NEAR(a.seen_area_m2, 0.4 * 0.3, 0.01);  // the top face
    // A second device at the same place changes nothing.
    EXPECT_NEAR(v.seen_by({v.camera, v.camera}, v.T_world_view).seen_area_m2, a.seen_area_m2, 1e-9);
    // A device 0.5 m to the side, looking parallel: it sees only part of the top, so the
    // sensor measures only the part both see.
    VisibilityDevice aside = v.camera;
    aside.T_view_device.translation() = Eigen::Vector3d(0.5, 0.0, 0.0);
    const VisibilityAgreement b = v.seen_by({v.camera, aside}, v.T_world_view);
    EXPECT_GT(b.seen_area_m2, 0.02);
    EXPECT_LT(b.seen_area_m2, a.seen_area_m2 - 0.02);
    // A device looking the other way sees none of it.
    VisibilityDevice backward = v.camera;
    backward.T_view_device.linear() =
        Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitY()).matrix();
    EXPECT_EQ(v.seen_by({v.camera, backward}, v.T_world_view).seen_area_m2, 0.0);
}

TEST(TruthVisibility, AreaIsBandedByIncidenceAndGrazingLiesBetweenTheLimits) {
    const TopView v;
    const VisibilityAgreement a = v.seen_by({v.camera}, v.T_world_view);
    // The top lies within 14 degrees of the view, the top hides the sides.
    double total = 0.0, below_15 = 0.0;
    for (const IncidenceBand& band : a.bands) {
        total += band.area_m2;
        if (band.to_deg <= 15.0) below_15 += band.area_m2;
    }
    EXPECT_NEAR(total, a.seen_area_m2 + a.grazing_area_m2 + a.unseen_area_m2, 1e-9);
    EXPECT_NEAR(below_15, a.seen_area_m2, 1e-9);
    // From 0.4 m beyond the +x side, that side faces the view at 68 to 72 degrees: the part
    // beyond 70 degrees is grazing (between the default limits), unless the limits are one.
    const Pose beside = TopView::looking_down_from(0.6);
    const VisibilityAgreement g = v.seen_by({v.camera}, beside);
    EXPECT_GT(g.grazing_area_m2, 0.01);
    EXPECT_LT(g.grazing_area_m2, 0.2 * 0.3);
    const VisibilityAgreement h = v.seen_by({v.camera}, beside, 75.0, 75.0);
    EXPECT_EQ(h.grazing_area_m2, 0.0);
    EXPECT_NEAR(h.seen_area_m2, g.seen_area_m2 + g.grazing_area_m2, 1e-9);
}

}  // namespace
}  // namespace anascan
