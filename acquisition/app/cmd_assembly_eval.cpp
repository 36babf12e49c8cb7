// anascan blocks eval ASSEMBLY/ --truth DIR/truth.json [--json]: an assembly of blocks
// assemble against the simulated monument's truth. A model (blocks/ID.ply of sim
// export-monument) is in the block's fallen pose, so its true assembly pose is
// T_monument_block · T_ground_block⁻¹; poses are compared relative to the first fixed
// block: per block the rotation error and the displacement of the block's centre.
#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <map>

#include "anascan/processing/core/pose.hpp"
#include "block_features_json.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

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

}  // namespace

void run_assembly_eval(const std::string& dir, const std::string& truth_path, bool as_json) {
    auto report = read_json_file(std::filesystem::path(dir) / "assembly.json");
    if (!report) fail_command(report.error());
    auto truth = read_json_file(truth_path);
    if (!truth) fail_command(truth.error());
    try {
        const auto blocks = true_blocks(*truth);
        const json& placed = report->at("blocks");
        std::string anchor;
        for (const json& b : placed)
            if (b.at("fixed").get<bool>() && anchor.empty()) anchor = b.at("id").get<std::string>();
        if (!blocks.contains(anchor))
            fail_command({ErrorCode::kFormat, truth_path + ": no block " + anchor});
        Pose T_anchor = Pose::Identity();
        for (const json& b : placed)
            if (b.at("id") == anchor) T_anchor = pose_from_rows(b.at("T_assembly_model"));
        json per = json::array();
        double worst_rot = 0.0, worst_trans = 0.0;
        for (const json& b : placed) {
            const std::string id = b.at("id").get<std::string>();
            if (!blocks.contains(id))
                fail_command({ErrorCode::kFormat, truth_path + ": no block " + id});
            const Pose truth_rel = blocks.at(anchor).T_truth.inverse() * blocks.at(id).T_truth;
            const Pose rel = T_anchor.inverse() * pose_from_rows(b.at("T_assembly_model"));
            const Pose E = truth_rel.inverse() * rel;
            const Eigen::Vector3d c = blocks.at(id).centre_model;
            const double rot = rotation_angle_deg(E), trans = (E * c - c).norm();
            worst_rot = std::max(worst_rot, rot), worst_trans = std::max(worst_trans, trans);
            per.push_back(
                {{"id", id}, {"rotation_error_deg", rot}, {"translation_error_mm", 1e3 * trans}});
        }
        const json& check = report->at("check");
        const json out{{"status", report->at("status")},
                       {"fixed", anchor},
                       {"blocks", per},
                       {"worst_rotation_error_deg", worst_rot},
                       {"worst_translation_error_mm", 1e3 * worst_trans},
                       {"penetration_max_mm", check.at("penetration_max_mm")},
                       {"penetration_mean_mm", check.at("penetration_mean_mm")}};
        if (as_json) {
            std::printf("%s\n", out.dump(1).c_str());
            return;
        }
        for (const json& b : per)
            std::printf("%-8s rotation %.3f deg, centre %.2f mm\n",
                        b["id"].get<std::string>().c_str(), b["rotation_error_deg"].get<double>(),
                        b["translation_error_mm"].get<double>());
        std::printf(
            "%zu blocks against the truth (relative to %s): worst %.3f deg, %.2f mm; penetration "
            "max %.3f mm, "
            "mean %.3f mm; status %s\n",
            per.size(), anchor.c_str(), worst_rot, 1e3 * worst_trans,
            check.at("penetration_max_mm").get<double>(),
            check.at("penetration_mean_mm").get<double>(),
            report->at("status").get<std::string>().c_str());
    } catch (const json::exception& e) {
        fail_command(
            {ErrorCode::kFormat, dir + "/assembly.json / " + truth_path + ": " + e.what()});
    }
}

}  // namespace anascan::cli
