#pragma once
/// \file
/// Line geometry of the hole markers (private): per hole a ring of the hole's equivalent
/// radius in its tangent plane and a normal stick, as GL_LINES vertex pairs.

#include <span>
#include <vector>

#include "anascan/gui/point_renderer.hpp"

namespace anascan::gui::detail {

struct MarkerLines {
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();  ///< Vertices are relative to it.
    std::vector<Eigen::Vector3f> vertices;               ///< Pairs, one per line segment.
};

MarkerLines hole_marker_lines(std::span<const HoleMarker> holes);

}  // namespace anascan::gui::detail
