#pragma once
/// \file
/// Fragment models of placed scans: `anascan mesh` (scans placed by a .conf), `session
/// export --mesh` and the field app's mesh view (a session's model group) all load, place
/// and mesh their scans here, with processing's reconstruct_surface.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "anascan/acquisition/assembly/assembly.hpp"
#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/surface/reconstruction.hpp"

namespace anascan::acquisition {

/// One scan to mesh: its file, its pose and, when known, its sensor position.
struct MeshScan {
    std::filesystem::path file;
    Pose T_world_scan = Pose::Identity();
    std::optional<Eigen::Vector3d> sensor_scan_m;  ///< Sensor position in the scan frame.
    std::int64_t seq = 0;                          ///< A session's scan: its seq (else 0).
};

/// The surface and the scans it was made of.
struct MeshedScans {
    SurfaceResult surface;           ///< Status kOk.
    std::vector<std::string> files;  ///< The scans used (those with finite points).
};

/// Loads each PLY, drops non-finite points (a scan with none is left out, with a
/// progress message), places it and reconstructs the surface. Errors name the file; a
/// reconstruction that fails (no points, an isolated scan, ...) is an error naming the
/// reason and the scans concerned.
Expected<MeshedScans> mesh_scans(std::span<const MeshScan> scans, const SurfaceConfig& config,
                                 const ProgressFn& progress = {});

/// A session group's scans to mesh.
struct SessionMeshScans {
    int group = -1;
    std::vector<MeshScan> scans;
};

/// The scans of `group` that are registered, not excluded and placed (-1: the model group,
/// the largest), in the session's frame, with their recorded sensor origins.
Expected<SessionMeshScans> session_mesh_scans(const SessionStore& store, int group = -1);

}  // namespace anascan::acquisition
