#pragma once
/// \file
/// A stone-centred, ground-aligned frame for exported models: what a user expects when
/// opening the model in MeshLab or CloudCompare (the stone upright at the origin), instead
/// of the frame of the first scan (tilted, about a metre away).

#include <string>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/core/pose.hpp"

namespace anascan::acquisition {

struct StoneFrameConfig {
    double ground_band_m = 0.004;       ///< Ground plane inlier band half-width, metres.
    double min_ground_fraction = 0.05;  ///< Of the model's points, to trust the plane.
};

struct StoneFrame {
    /// Model frame -> stone frame: +z up (away from the ground), origin on the ground under
    /// the stone's centroid, +x along the stone's longest horizontal extent.
    Pose T_stone_model = Pose::Identity();
    bool ground_found = false;  ///< Else +z is the stone's direction of least extent.
    std::string description;    ///< For the user: how the frame was chosen.
};

/// The frame of a merged model (points of the stone and, usually, of the ground it lies
/// on). Without a ground plane, the frame is the stone's principal axes at its centroid.
StoneFrame stone_frame(const PointCloud& model, const StoneFrameConfig& config = {});

}  // namespace anascan::acquisition
