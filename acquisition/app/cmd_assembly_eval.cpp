// anascan blocks eval ASSEMBLY/ --truth DIR/truth.json [--json]: an assembly of blocks
// assemble against the simulated monument's truth. A model (blocks/ID.ply of sim
// export-monument) is in the block's fallen pose, so its true assembly pose is
// T_monument_block · T_ground_block⁻¹; poses are compared relative to the first fixed
// block: per block the rotation error and the displacement of the block's centre.
#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <map>

#include "anascan/acquisition/blocks/block_features_file.hpp"
#include "anascan/processing/core/pose.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

using namespace anascan::acquisition;  // The blocks folder's files.

using nlohmann::json;

Pose pose_from_rows(const json& rows) {
    Pose T = Pose::Identity();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) T.matrix()(r, c) = rows.at(r).at(c).get<double>();
    return T;
}

struct TrueBlock {
    Pose T_truth;  ///< Model (fallen) frame to the monument.
    Eigen::Vector3d centre_model;
};

std::map<std::string, TrueBlock> true_blocks(const json& truth) {
    std::map<std::string, TrueBlock> out;
    for (const json& b : truth.at("blocks")) {
        const Pose T_ground = pose_from_rows(b.at("T_ground_block"));
        out[b.at("id").get<std::string>()] = {
            pose_from_rows(b.at("T_monument_block")) * T_ground.inverse(), T_ground.translation()};
    }
    return out;
}

/// The first fixed block of the assembly: the frame both sides are compared in.
std::string anchor_block(const json& placed) {
    for (const json& b : placed)
        if (b.at("fixed").get<bool>()) return b.at("id").get<std::string>();
    return {};
}

struct BlockErrors {
    json per = json::array();
    double worst_rot_deg = 0.0, worst_trans_m = 0.0;
};

/// Each block's pose relative to the anchor, against the truth's (translation at its centre).
BlockErrors block_errors(const json& placed, const std::map<std::string, TrueBlock>& blocks,
                         const std::string& anchor, const std::string& truth_path) {
    Pose T_anchor = Pose::Identity();
    for (const json& b : placed)
        if (b.at("id") == anchor) T_anchor = pose_from_rows(b.at("T_assembly_model"));
    BlockErrors out;
    for (const json& b : placed) {
        const std::string id = b.at("id").get<std::string>();
        if (!blocks.contains(id))
            fail_command({ErrorCode::kFormat, truth_path + ": no block " + id});
        const Pose truth_rel = blocks.at(anchor).T_truth.inverse() * blocks.at(id).T_truth;
        const Pose rel = T_anchor.inverse() * pose_from_rows(b.at("T_assembly_model"));
        const Pose E = truth_rel.inverse() * rel;
        const Eigen::Vector3d c = blocks.at(id).centre_model;
        const double rot = rotation_angle_deg(E), trans = (E * c - c).norm();
        out.worst_rot_deg = std::max(out.worst_rot_deg, rot);
        out.worst_trans_m = std::max(out.worst_trans_m, trans);
        out.per.push_back(
            {{"id", id}, {"rotation_error_deg", rot}, {"translation_error_mm", 1e3 * trans}});
    }
    return out;
}

void print_errors(const json& out) {
    for (const json& b : out.at("blocks"))
        std::printf("%-8s rotation %.3f deg, centre %.2f mm\n", b["id"].get<std::string>().c_str(),
                    b["rotation_error_deg"].get<double>(), b["translation_error_mm"].get<double>());
    std::printf(
        "%zu blocks against the truth (relative to %s): worst %.3f deg, %.2f mm; penetration "
        "max %.3f mm, mean %.3f mm; status %s\n",
        out.at("blocks").size(), out.at("fixed").get<std::string>().c_str(),
        out.at("worst_rotation_error_deg").get<double>(),
        out.at("worst_translation_error_mm").get<double>(),
        out.at("penetration_max_mm").get<double>(), out.at("penetration_mean_mm").get<double>(),
        out.at("status").get<std::string>().c_str());
}

}  // namespace

void run_assembly_eval(const std::string& dir, const std::string& truth_path, bool as_json) {
    auto report = read_json_file(std::filesystem::path(dir) / "assembly.json");
    if (!report) fail_command(report.error());
    auto truth = read_json_file(truth_path);
    if (!truth) fail_command(truth.error());
    try {
        const auto blocks = true_blocks(*truth);
        const json& placed = report->at("blocks");
        const std::string anchor = anchor_block(placed);
        if (!blocks.contains(anchor))
            fail_command({ErrorCode::kFormat, truth_path + ": no block " + anchor});
        const BlockErrors errors = block_errors(placed, blocks, anchor, truth_path);
        const json& check = report->at("check");
        const json out{{"status", report->at("status")},
                       {"fixed", anchor},
                       {"blocks", errors.per},
                       {"worst_rotation_error_deg", errors.worst_rot_deg},
                       {"worst_translation_error_mm", 1e3 * errors.worst_trans_m},
                       {"penetration_max_mm", check.at("penetration_max_mm")},
                       {"penetration_mean_mm", check.at("penetration_mean_mm")}};
        if (as_json)
            std::printf("%s\n", out.dump(1).c_str());
        else
            print_errors(out);
    } catch (const json::exception& e) {
        fail_command(
            {ErrorCode::kFormat, dir + "/assembly.json / " + truth_path + ": " + e.what()});
    }
}

}  // namespace anascan::cli
