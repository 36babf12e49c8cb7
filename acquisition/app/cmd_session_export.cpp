// anascan session export DIR --out MODEL.ply: the registered scans of the largest group
// merged, in a stone-centred frame (--frame stone, the default) or their group's frame,
// optionally with their poses as a Stanford .conf; --truth-poses writes the
// simulator's true poses of a simulated session as a .conf (for `anascan eval`).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <map>
#include <optional>

#include "anascan/acquisition/assembly/assembly.hpp"
#include "anascan/acquisition/assembly/stone_frame.hpp"
#include "anascan/acquisition/store/groups.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "commands.hpp"
#include "mesh_runner.hpp"
#include "point_files.hpp"
#include "session_cli.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;
using acquisition::ScanRecord;
using acquisition::ScanState;

struct ExportOptions {
    std::string dir;
    std::string out;
    std::string poses;
    std::string truth_poses;
    MeshOptions mesh;
    double voxel_mm = 0.0;
    bool include_failed = false;
    std::optional<int> group;
    std::string frame = "stone";  ///< "stone" (stone_frame) or "group" (its first scan's).
};

std::optional<Pose> export_pose(const ScanRecord& r, int group, bool include_failed) {
    if (r.excluded) return std::nullopt;
    if (r.state == ScanState::kRegistered) {
        return r.group == group ? r.pose : std::nullopt;
    }
    if (r.state != ScanState::kFailed || !include_failed) return std::nullopt;
    if (r.pose && r.group == group) return r.pose;
    return r.pose_prior;  // The device's own pose, if it gave one.
}

std::vector<io::ConfEntry> select_scans(const std::vector<ScanRecord>& scans, int group,
                                        bool include_failed) {
    std::vector<io::ConfEntry> entries;
    for (const ScanRecord& r : scans) {
        if (auto pose = export_pose(r, group, include_failed)) {
            entries.push_back({r.file, *pose});
        } else if (r.state == ScanState::kFailed && include_failed && !r.excluded) {
            spdlog::warn("scan {} failed and has no pose: left out", r.seq);
        }
    }
    return entries;
}

void write_poses(const fs::path& conf_path, const fs::path& dir,
                 const std::vector<io::ConfEntry>& entries, const char* what = "poses") {
    const fs::path conf_dir = fs::absolute(conf_path).parent_path();
    io::StanfordConf conf;
    for (const io::ConfEntry& e : entries) {
        const fs::path file = fs::absolute(dir / e.file).lexically_normal();
        const std::string name = file.lexically_relative(conf_dir).generic_string();
        if (name.find_first_of(" \t") != std::string::npos) {
            throw CommandFailed(conf_path.string() + ": a .conf cannot name '" + name +
                                "' (it has a space): write the .conf where the path to the "
                                "scans has no space");
        }
        conf.entries.push_back({name, e.T_world_scan});
    }
    if (auto ok = io::write_conf(conf_path, conf); !ok) fail_command(ok.error());
    std::printf("%s: %s (%zu scans)\n", what, conf_path.c_str(), conf.entries.size());
}

/// Every scan file with a true pose (simulated sessions), excluded or not: the files
/// `anascan register DIR/scans/*.ply` would read.
void write_truth_poses(const ExportOptions& o) {
    auto store = open_session(o.dir, acquisition::SessionOpenMode::kReadOnly);
    auto scans = store->scans();
    if (!scans) fail_command(scans.error());
    std::vector<io::ConfEntry> entries;
    for (const ScanRecord& r : *scans) {
        if (r.true_pose) entries.push_back({r.file, *r.true_pose});
    }
    if (entries.empty()) {
        throw CommandFailed(o.dir + ": no scan has a true pose (only simulated sessions have)");
    }
    write_poses(o.truth_poses, o.dir, entries, "true poses");
}

// The fragment model of the exported scans, each oriented with its recorded sensor origin.
void export_mesh(const ExportOptions& o, const std::vector<ScanRecord>& scans,
                 const std::vector<io::ConfEntry>& entries) {
    std::map<std::string, std::optional<Eigen::Vector3d>> sensors;
    for (const ScanRecord& r : scans) sensors[r.file] = r.sensor_origin_scan_m;
    std::vector<MeshScanEntry> mesh_entries;
    for (const io::ConfEntry& e : entries) {
        mesh_entries.push_back({fs::path(o.dir) / e.file, e.T_world_scan, sensors[e.file]});
    }
    run_mesh(mesh_entries, o.mesh);
}

/// The entries of the group to export, warning about registered scans left out.
std::vector<io::ConfEntry> group_entries(const ExportOptions& o,
                                         const std::vector<ScanRecord>& scans, int group) {
    auto entries = select_scans(scans, group, o.include_failed);
    if (entries.empty()) {
        throw CommandFailed(o.dir + ": no registered scan" +
                            (o.group ? " in group " + std::to_string(group) : "") +
                            " to export (see `anascan session info " + o.dir + "`)");
    }
    for (const ScanRecord& r : scans) {
        if (acquisition::counts_in_group(r) && r.group != group)
            spdlog::warn("scan {} is in group {}, not exported (use --group)", r.seq, r.group);
    }
    return entries;
}

/// Moves the model and the poses into the stone frame (--frame stone).
void to_stone_frame(PointCloud& model, std::vector<io::ConfEntry>& entries) {
    const acquisition::StoneFrame frame = acquisition::stone_frame(model);
    model = transformed(model, frame.T_stone_model);
    for (io::ConfEntry& e : entries) e.T_world_scan = frame.T_stone_model * e.T_world_scan;
    std::printf("%s\n", frame.description.c_str());
}

void check_export_outputs(const ExportOptions& o) {
    if (o.out.empty() && o.truth_poses.empty() && o.mesh.out.empty()) {
        throw CommandFailed(
            "session export: give --out MODEL.ply, --mesh MESH.ply and/or --truth-poses "
            "TRUTH.conf");
    }
    if (!o.out.empty()) check_point_output(o.out);
    check_output_writable(o.out, "--out");
    check_output_writable(o.mesh.out, "--mesh");
    check_output_writable(o.poses, "--poses");
    check_output_writable(o.truth_poses, "--truth-poses");
}

// The model (and the mesh) of the chosen group, in the frame asked for: the stone frame
// needs the assembled model, so the scans are assembled for a mesh alone too.
void run_export(const ExportOptions& o) {
    check_export_outputs(o);
    if (!o.truth_poses.empty()) write_truth_poses(o);
    if (o.out.empty() && o.mesh.out.empty()) return;
    auto store = open_session(o.dir, acquisition::SessionOpenMode::kReadOnly);
    auto scans = store->scans();
    if (!scans) fail_command(scans.error());
    const int group = o.group.value_or(acquisition::largest_group(*scans));
    auto entries = group_entries(o, *scans, group);
    acquisition::AssemblyConfig config{.model_voxel_m = o.voxel_mm * 1e-3, .measure_pairs = false};
    auto report = acquisition::assemble_entries(o.dir, entries, config,
                                                [](std::string_view m) { spdlog::debug("{}", m); });
    if (!report) fail_command(report.error());
    if (o.frame == "stone") to_stone_frame(report->model, entries);
    if (!o.out.empty()) {
        write_points(o.out, report->model);
        std::printf("model: %s (%zu points from %zu scans of group %d, %s frame)\n", o.out.c_str(),
                    report->model.size(), entries.size(), group, o.frame.c_str());
    }
    if (!o.poses.empty()) write_poses(o.poses, o.dir, entries);
    if (!o.mesh.out.empty()) export_mesh(o, *scans, entries);
}

}  // namespace

void add_session_export_command(CLI::App& session) {
    auto o = std::make_shared<ExportOptions>();
    auto* cmd = session.add_subcommand(
        "export",
        "Merge the registered, non-excluded scans of a session (placed by their poses) into "
        "one model, in a stone-centred, ground-aligned frame by default");
    cmd->add_option("dir", o->dir, "Session folder")->required();
    cmd->add_option("--out", o->out, "Merged model (.ply, or .xyz/.txt/.asc for XYZ text)");
    cmd->add_option("--frame", o->frame,
                    "Frame of the model and poses: stone (default: upright on the ground at "
                    "the origin, as MeshLab or CloudCompare users expect) or group (the "
                    "frame of the group's first scan, as registered)")
        ->check(CLI::IsMember({"stone", "group"}));
    cmd->add_option("--poses", o->poses,
                    "Also write the poses as a Stanford .conf (scan files named relative to it)");
    cmd->add_option("--truth-poses", o->truth_poses,
                    "Write the simulator's true poses of every scan as a Stanford .conf "
                    "(scan files named relative to it, as `anascan register` names them; "
                    "simulated sessions only), for `anascan eval`");
    cmd->add_option("--mesh", o->mesh.out,
                    "Also write the fragment model (.ply, .obj or .stl; see `anascan mesh`)");
    add_mesh_options(cmd, o->mesh);
    cmd->add_option("--voxel-mm", o->voxel_mm, "Down-sample the model to this voxel size, mm")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--group", o->group, "Export this registration group (default: the largest)");
    cmd->add_flag("--include-failed", o->include_failed,
                  "Also place failed scans that have a pose (registered or from the device)");
    cmd->callback([o] { run_export(*o); });
}

}  // namespace anascan::cli
