#include "scan_region.hpp"

#include <spdlog/spdlog.h>

#include "anascan/processing/cleaning/plane_removal.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

bool in_region(const Eigen::Vector3d& p, const RegionOptions& region) {
    if (!region.box_m.empty()) {
        for (int k = 0; k < 3; ++k)
            if (p[k] < region.box_m[k] || p[k] > region.box_m[k + 3]) return false;
    }
    if (!region.range_m.empty()) {
        const double distance = p.norm();
        if (distance < region.range_m[0] || distance > region.range_m[1]) return false;
    }
    return true;
}

}  // namespace

void add_region_options(CLI::App* cmd, RegionOptions& options) {
    cmd->add_option("--roi-box", options.box_m,
                    "Register only the points inside this box of each scan's own frame: XMIN "
                    "YMIN ZMIN XMAX YMAX ZMAX, metres")
        ->expected(6);
    cmd->add_option("--roi-range-m", options.range_m,
                    "Register only the points at a distance MIN..MAX metres from each scan "
                    "frame's origin (where the sensor sits for most scanners)")
        ->expected(2);
    cmd->add_flag("--remove-background-plane", options.remove_background_plane,
                  "Drop each scan's dominant plane (a wall or floor behind the object) before "
                  "registering, so that the static background cannot decide the pose");
}

PointCloud select_region(const PointCloud& cloud, const RegionOptions& region,
                         const std::string& path) {
    const bool box_or_range = !region.box_m.empty() || !region.range_m.empty();
    if (!box_or_range && !region.remove_background_plane) return cloud;
    PointCloud selected = cloud;
    if (box_or_range) {
        std::vector<std::size_t> keep;
        for (std::size_t i = 0; i < cloud.size(); ++i)
            if (in_region(cloud.world_position(i), region)) keep.push_back(i);
        selected = select(cloud, keep);
        spdlog::info("{}: {} of {} points in the region of interest", path, keep.size(),
                     cloud.size());
    }
    if (region.remove_background_plane) {
        const PlaneRemovalResult removal = remove_dominant_plane(selected, {});
        if (removal.fit.status == PlaneFitStatus::kOk) {
            spdlog::info("{}: background plane removed ({} points)", path,
                         selected.size() - removal.kept_indices.size());
            selected = select(selected, removal.kept_indices);
        } else {
            spdlog::warn("{}: no dominant plane to remove", path);
        }
    }
    if (selected.empty() && !cloud.empty())
        throw CommandFailed(path + ": no point left in the region of interest");
    return selected;
}

}  // namespace anascan::cli
