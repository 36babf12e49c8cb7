#pragma once
/// \file
/// The model report (paper §4.3): is the mesh closed, manifold and one piece; its area,
/// volume and oriented bounding box; how much of it was interpolated and where the holes
/// of the measured surface are; and how closely it follows the scans.

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "anascan/processing/surface/fragment_model.hpp"
#include "anascan/processing/surface/reconstruction.hpp"

namespace anascan {

/// A hole of the measured surface: a boundary loop of its measured triangles.
struct HoleReport {
    double area_m2 = 0.0;      ///< Area of the fan that closes the loop from its centroid.
    double perimeter_m = 0.0;  ///< Length of the outline.
    std::size_t outline_vertices = 0;
    Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();  ///< World frame.
    std::vector<Eigen::Vector3d> outline_m;                ///< The loop, world frame.
};

struct ModelReport {
    std::size_t vertices = 0, triangles = 0;
    bool closed = false;    ///< No boundary edge and no edge used three times.
    bool manifold = false;  ///< Edge- and vertex-manifold, consistently wound.
    std::size_t components = 0;
    double area_m2 = 0.0;
    double volume_m3 = 0.0;  ///< Enclosed volume (meaningful when closed).
    Eigen::Vector3d obb_mm = Eigen::Vector3d::Zero();  ///< OBB edge lengths, longest first.
    double interpolated_area_share = 0.0;              ///< 0..1 of the area.
    std::vector<HoleReport> holes;                     ///< Largest first.
    double accuracy_median_m = 0.0;  ///< Measured vertices to the merged scans, along normals.
    double accuracy_p95_m = 0.0;
    std::size_t accuracy_samples = 0;
};

/// Surface area (m^2) and enclosed volume (m^3, divergence theorem) of a mesh.
double mesh_area_m2(const Mesh& mesh);
double mesh_volume_m3(const Mesh& mesh);

/// Edge lengths (mm, longest first) of the box aligned with the area-weighted principal
/// axes of the surface.
Eigen::Vector3d oriented_box_mm(const Mesh& mesh);

/// Builds the report of `model`; `merged` (oriented normals) is what accuracy is measured
/// against.
ModelReport make_model_report(const FragmentModel& model, const PointCloud& merged);

/// The report as a plain-text table for a terminal.
std::string model_report_table(const ModelReport& report);

}  // namespace anascan
