#pragma once
/// \file
/// The fragment model of the view's group, made at the operator's request on a worker
/// thread (acquisition's mesh_scans, as `anascan session export --mesh` makes it: seconds
/// to tens of seconds). The stage reached shows while it runs; the finished mesh is handed
/// to the UI thread once, for the GPU. A mesh made before newer scans joined says so.

#include <cstdint>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/gui/field_view_state.hpp"
#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/surface/model_report.hpp"

namespace anascan::field {

class MeshMaker {
public:
    MeshMaker(int worker_nice, double resolution_mm)
        : worker_nice_(worker_nice), resolution_mm_(resolution_mm) {}
    ~MeshMaker();
    MeshMaker(const MeshMaker&) = delete;
    MeshMaker& operator=(const MeshMaker&) = delete;

    /// Starts meshing the store's model group; ignored while a mesh is being made.
    void start(const acquisition::SessionStore* store, gui::MeshViewState& view);
    /// The stage reached, the figures once done, and whether the view's scans have moved on.
    void poll(gui::MeshViewState& view, const std::vector<gui::ScanRow>& rows);
    /// The finished mesh, once (then nothing until the next).
    std::optional<Mesh> take_mesh() { return std::exchange(finished_, std::nullopt); }
    bool settled() const { return !pending_; }

private:
    struct Made {
        Mesh mesh;
        ModelReport report;
        double seconds = 0.0;
    };
    struct Stage {
        std::mutex mutex;
        std::string text;
    };

    int worker_nice_ = 10;
    double resolution_mm_ = 1.0;
    std::shared_ptr<Stage> stage_ = std::make_shared<Stage>();
    std::optional<std::future<Expected<Made>>> pending_;
    std::optional<Mesh> finished_;
    int group_ = -1;                ///< The group it is made of.
    std::set<std::int64_t> scans_;  ///< The scans it is made of.
};

}  // namespace anascan::field
