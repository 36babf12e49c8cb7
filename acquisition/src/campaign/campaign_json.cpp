#include "campaign/campaign_json.hpp"

#include "anascan/acquisition/campaign/campaign_store.hpp"

namespace anascan::acquisition::campaign_json {

nlohmann::json pose(const Pose& T) {
    nlohmann::json rows = nlohmann::json::array();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) rows.push_back(T.matrix()(i, j));
    return rows;
}

Pose pose_from(const nlohmann::json& rows) {
    Pose T = Pose::Identity();
    if (!rows.is_array() || rows.size() != 16) return T;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) T.matrix()(i, j) = rows[static_cast<std::size_t>(4 * i + j)];
    return T;
}

nlohmann::json summary(const PreparedSummary& s) {
    return {{"points", s.points},
            {"spacing_m", s.spacing_m},
            {"centre_m", {s.centre_m.x(), s.centre_m.y(), s.centre_m.z()}},
            {"diagonal_m", s.diagonal_m},
            {"position_hash", s.position_hash},
            {"normals_estimated", s.normals_estimated},
            {"problem", s.problem}};
}

PreparedSummary summary_from(const nlohmann::json& j) {
    PreparedSummary s;
    s.points = j.value("points", std::size_t{0});
    s.spacing_m = j.value("spacing_m", 0.0);
    if (j.contains("centre_m") && j["centre_m"].size() == 3) {
        s.centre_m = Eigen::Vector3d(j["centre_m"][0].get<double>(), j["centre_m"][1].get<double>(),
                                     j["centre_m"][2].get<double>());
    }
    s.diagonal_m = j.value("diagonal_m", 0.0);
    s.position_hash = j.value("position_hash", std::uint64_t{0});
    s.normals_estimated = j.value("normals_estimated", false);
    s.problem = j.value("problem", std::string());
    return s;
}

CampaignPairResult pair_from(const nlohmann::json& j) {
    CampaignPairResult r;
    r.status = static_cast<GlobalRegistrationStatus>(
        j.value("status_code", static_cast<int>(GlobalRegistrationStatus::kInvalidInput)));
    r.verified = j.value("verified", false);
    if (j.contains("T_target_source")) r.T_target_source = pose_from(j["T_target_source"]);
    r.rms_m = j.value("rms_m", 0.0);
    r.overlap_fraction = j.value("overlap", 0.0);
    r.target_spacing_m = j.value("target_spacing_m", 0.0);
    r.slide_ambiguous = j.value("slide_ambiguous", false);
    r.time_s = j.value("time_s", 0.0);
    return r;
}

Error damaged(const CampaignStore& store, const std::string& what, const Error& problem) {
    const std::string dir = store.dir().string();
    return Error{ErrorCode::kFormat,
                 dir + "/campaign.sqlite: " + (what.empty() ? "" : what + ": ") + problem.message +
                     " (run `anascan campaign check " + dir +
                     " --repair`, then `anascan campaign register " + dir + "` redoes that work)"};
}

}  // namespace anascan::acquisition::campaign_json
