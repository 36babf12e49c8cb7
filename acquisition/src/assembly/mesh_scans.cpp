#include "anascan/acquisition/assembly/mesh_scans.hpp"

#include <string>

#include "anascan/acquisition/store/groups.hpp"
#include "anascan/processing/io/ply.hpp"

namespace anascan::acquisition {
namespace {

struct LoadedScans {
    std::vector<PointCloud> clouds;  ///< World frame.
    std::vector<std::optional<Eigen::Vector3d>> sensors_world_m;
    std::vector<std::string> files;
};

void say(const ProgressFn& progress, const std::string& message) {
    if (progress) progress(message);
}

Expected<LoadedScans> load_placed(std::span<const MeshScan> scans, const ProgressFn& progress) {
    LoadedScans s;
    s.clouds.reserve(scans.size());
    for (const MeshScan& e : scans) {
        auto ply = io::read_ply(e.file);
        if (!ply) return fail(ply.error());
        PointCloud cloud = std::move(ply->cloud);
        const std::size_t bad = remove_non_finite(cloud);
        if (cloud.empty()) {
            say(progress, e.file.string() + ": no finite points (" + std::to_string(bad) +
                              " non-finite): left out");
            continue;
        }
        say(progress, "loaded " + e.file.filename().string() + " (" + std::to_string(cloud.size()) +
                          " points)");
        s.clouds.push_back(transformed(cloud, e.T_world_scan));
        s.files.push_back(e.file.string());
        std::optional<Eigen::Vector3d> sensor;
        if (e.sensor_scan_m) sensor = e.T_world_scan * *e.sensor_scan_m;
        s.sensors_world_m.push_back(sensor);
    }
    return s;
}

Error reconstruction_error(const SurfaceResult& r, const LoadedScans& s) {
    std::string message = "cannot mesh: " + std::string(to_string(r.status));
    for (const std::size_t i : r.diagnostics.isolated_scans) message += "; " + s.files[i];
    if (!r.diagnostics.poisson_error.empty()) message += ": " + r.diagnostics.poisson_error;
    if (r.status == SurfaceStatus::kTooFewPoints) {
        message += " (" + std::to_string(r.diagnostics.merged_points) + " cells occupied)";
    }
    return Error{
        r.status == SurfaceStatus::kNoPoints ? ErrorCode::kEmpty : ErrorCode::kInvalidArgument,
        message};
}

}  // namespace

Expected<MeshedScans> mesh_scans(std::span<const MeshScan> scans, const SurfaceConfig& config,
                                 const ProgressFn& progress) {
    auto loaded = load_placed(scans, progress);
    if (!loaded) return fail(loaded.error());
    if (loaded->clouds.empty())
        return fail(ErrorCode::kEmpty, "cannot mesh: no scan has a finite point");
    std::vector<PlacedScan> placed;
    for (std::size_t i = 0; i < loaded->clouds.size(); ++i)
        placed.push_back({&loaded->clouds[i], loaded->sensors_world_m[i]});
    MeshedScans out{.surface = reconstruct_surface(placed, config, progress),
                    .files = std::move(loaded->files)};
    if (out.surface.status != SurfaceStatus::kOk)
        return fail(reconstruction_error(out.surface, *loaded));
    return out;
}

Expected<SessionMeshScans> session_mesh_scans(const SessionStore& store, int group) {
    auto records = store.scans();
    if (!records) return fail(records.error());
    if (group < 0) group = largest_group(*records);
    std::vector<MeshScan> out;
    for (const ScanRecord& r : *records) {
        if (!counts_in_group(r) || r.group != group || !r.pose) continue;
        out.push_back({store.dir() / r.file, *r.pose, r.sensor_origin_scan_m, r.seq});
    }
    if (out.empty())
        return fail(ErrorCode::kEmpty,
                    store.dir().string() + ": no registered scan to mesh" +
                        (group >= 0 ? " in group " + std::to_string(group) : ""));
    return SessionMeshScans{.group = group, .scans = std::move(out)};
}

}  // namespace anascan::acquisition
