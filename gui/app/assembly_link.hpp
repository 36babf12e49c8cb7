#pragma once
/// \file
/// The assembly view's link to acquisition: the folder of block features loaded, the
/// alignment run and the accepted result written, each on a worker thread at a lower
/// priority (loading twelve blocks takes seconds, an alignment seconds to a minute: the UI
/// never waits). The UI thread polls: finished work moves into the view state and the
/// renderer, one block per chunk, at its model pose until aligned, then at its assembled
/// pose, coloured by gap and penetration.

#include <filesystem>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "anascan/acquisition/blocks/block_alignment.hpp"
#include "anascan/acquisition/blocks/block_proposals.hpp"
#include "anascan/gui/assembly_view.hpp"
#include "anascan/gui/point_renderer.hpp"
#include "anascan/gui/view_picking.hpp"

namespace anascan::field {

struct AssemblyLinkConfig {
    std::filesystem::path dir;                       ///< Folder of blocks features.
    std::optional<std::filesystem::path> proposals;  ///< Default: DIR/proposals.json if any.
    std::filesystem::path out;                       ///< Where "Accept" writes the assembly.
    std::vector<std::string> fixed;                  ///< Blocks held still (default: the first).
    int worker_nice = 10;
};

class AssemblyLink {
public:
    explicit AssemblyLink(AssemblyLinkConfig config);
    ~AssemblyLink();
    AssemblyLink(const AssemblyLink&) = delete;
    AssemblyLink& operator=(const AssemblyLink&) = delete;

    /// Reads the proposals (at once: a small file) and starts loading the blocks.
    void open(gui::AssemblyViewState& view);
    /// Moves finished work into the view and the renderer; true when the blocks moved or
    /// were recoloured (the camera may refit).
    bool poll(gui::AssemblyViewState& view, gui::PointRenderer& renderer);
    /// kAlignBlocks, kAcceptAssembly; false for other actions.
    bool apply(const gui::UiAction& action, gui::AssemblyViewState& view);
    /// No worker running.
    bool settled() const { return !loading_ && !aligning_ && !saving_; }
    /// The accepted pairs of the proposals (the headless operator chooses them).
    const std::vector<std::string>& accepted() const { return accepted_; }
    /// The face ("A:F") of the block point a click along `ray` lands on (within
    /// `radius_rad` of it, nearest the eye); empty when it hits no block, or no face.
    std::string pick_face(const gui::ViewRay& ray, double radius_rad) const;
    /// A block's centroid where the view shows it (the headless operator clicks there).
    std::optional<Eigen::Vector3d> shown_centre(const std::string& id) const;

private:
    struct Progress {
        std::mutex mutex;
        std::string text;
    };
    using Blocks = std::vector<reassembly::AssemblyBlock>;
    void start_alignment(gui::AssemblyViewState& view);
    void start_saving(gui::AssemblyViewState& view);
    void take_loaded(gui::AssemblyViewState& view, gui::PointRenderer& renderer);
    void take_aligned(gui::AssemblyViewState& view, gui::PointRenderer& renderer);
    void show_blocks(gui::PointRenderer& renderer) const;
    /// Where block b is drawn: its assembled pose once aligned, else where its model lies.
    Pose shown_pose(std::size_t b) const;

    AssemblyLinkConfig config_;
    std::shared_ptr<Progress> progress_ = std::make_shared<Progress>();
    std::optional<acquisition::BlockFolder> folder_;
    std::vector<std::string> accepted_;
    /// Every block of the folder, once loaded (only read afterwards).
    std::shared_ptr<const Blocks> blocks_;
    /// The blocks the chosen pairs name, as the last alignment solved them (and saves them).
    std::shared_ptr<const acquisition::LinkedBlocks> linked_;
    std::optional<acquisition::BlockAlignment> alignment_;
    std::optional<std::future<Expected<Blocks>>> loading_;
    std::optional<std::future<Expected<acquisition::BlockAlignment>>> aligning_;
    std::optional<std::future<Expected<void>>> saving_;
};

}  // namespace anascan::field
