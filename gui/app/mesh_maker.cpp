#include "mesh_maker.hpp"

#include <fmt/format.h>

#include "anascan/acquisition/assembly/mesh_scans.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "future_ready.hpp"
#include "thread_priority.hpp"

namespace anascan::field {

namespace {

/// "3 newer scans", "2 scans left the model", both, or empty.
std::string outdated_by(const std::set<std::int64_t>& meshed, int group,
                        const std::vector<gui::ScanRow>& rows) {
    int newer = 0, gone = 0;
    std::set<std::int64_t> in_group;
    for (const gui::ScanRow& row : rows) {
        const bool placed = row.state == gui::ScanRowState::kRegistered ||
                            row.state == gui::ScanRowState::kUnjoined;
        if (!placed || row.group != group) continue;
        in_group.insert(row.seq);
        newer += !meshed.contains(row.seq);
    }
    for (const std::int64_t seq : meshed) gone += !in_group.contains(seq);
    std::string text;
    if (newer > 0) text = fmt::format("{} newer scan{}", newer, newer == 1 ? "" : "s");
    if (gone > 0)
        text += fmt::format("{}{} scan{} left the model", text.empty() ? "" : ", ", gone,
                            gone == 1 ? "" : "s");
    return text;
}

}  // namespace

MeshMaker::~MeshMaker() {
    if (pending_) pending_->wait();
}

void MeshMaker::start(const acquisition::SessionStore* store, gui::MeshViewState& view) {
    if (pending_) return;
    if (store == nullptr) {
        view = {.status = gui::MeshViewState::Status::kFailed,
                .message = "no scans yet: capture first"};
        return;
    }
    auto session = acquisition::session_mesh_scans(*store);
    if (!session) {
        view = {.status = gui::MeshViewState::Status::kFailed, .message = session.error().message};
        return;
    }
    group_ = session->group;
    auto* scans = &session->scans;
    scans_.clear();
    for (const acquisition::MeshScan& s : *scans) scans_.insert(s.seq);
    view = {.status = gui::MeshViewState::Status::kMaking,
            .message = fmt::format("{} scans", scans->size()),
            .resolution_mm = resolution_mm_};
    const SurfaceConfig config{.resolution_m = resolution_mm_ * 1e-3};
    pending_ = std::async(
        std::launch::async,
        [stage = stage_, scans = std::move(*scans), config,
         nice = worker_nice_]() -> Expected<Made> {
            lower_this_thread_priority(nice);
            Stopwatch watch;
            auto meshed = acquisition::mesh_scans(scans, config, [&stage](std::string_view m) {
                std::lock_guard lock(stage->mutex);
                stage->text = std::string(m);
            });
            if (!meshed) return fail(meshed.error());
            Made made{.report = make_model_report(meshed->surface.model, meshed->surface.merged)};
            made.mesh = std::move(meshed->surface.model.mesh);
            made.seconds = watch.seconds();
            return made;
        });
}

void MeshMaker::poll(gui::MeshViewState& view, const std::vector<gui::ScanRow>& rows) {
    if (pending_ && !ready(pending_)) {
        std::lock_guard lock(stage_->mutex);
        if (!stage_->text.empty()) view.message = stage_->text;
        return;
    }
    if (pending_) {
        Expected<Made> made = pending_->get();
        pending_.reset();
        if (!made) {
            view.status = gui::MeshViewState::Status::kFailed;
            view.message = made.error().message;
            return;
        }
        const ModelReport& r = made->report;
        view.status = gui::MeshViewState::Status::kReady;
        view.message.clear();
        view.scans = static_cast<int>(scans_.size());
        view.triangles = r.triangles;
        view.area_m2 = r.area_m2;
        view.interpolated_share = r.interpolated_area_share;
        view.closed = r.closed && r.manifold && r.components == 1;
        view.seconds = made->seconds;
        finished_ = std::move(made->mesh);
    }
    if (view.status == gui::MeshViewState::Status::kReady)
        view.outdated = outdated_by(scans_, group_, rows);
}

}  // namespace anascan::field
