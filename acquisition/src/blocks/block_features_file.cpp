// Block features as JSON files (`anascan blocks features` writes them; the matcher, the
// assembly and the field app read them back).
#include "anascan/acquisition/blocks/block_features_file.hpp"

#include <Eigen/Geometry>
#include <algorithm>

namespace anascan::acquisition {
namespace {

using nlohmann::json;
using reassembly::BlockStatus;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
Eigen::Vector3d vec(const json& j) {
    return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

json hole_json(const reassembly::FaceHole& h) {
    return {{"kind", reassembly::to_string(h.kind)},
            {"centre_m", vec(h.centre_m)},
            {"face_uv_m", json::array({h.face_uv_m.x(), h.face_uv_m.y()})},
            {"length_m", h.length_m},
            {"width_m", h.width_m},
            {"depth_m", h.depth_m}};
}

json face_json(const reassembly::PlanarFace& f) {
    json holes = json::array();
    for (const auto& h : f.holes) holes.push_back(hole_json(h));
    return {{"id", f.id},
            {"normal", vec(f.normal)},
            {"offset_m", f.offset_m},
            {"centre_m", vec(f.centre_m)},
            {"width_axis", vec(f.width_axis)},
            {"width_m", f.width_m},
            {"height_m", f.height_m},
            {"area_m2", f.area_m2},
            {"roughness_per_m2", f.roughness_per_m2},
            {"rms_m", f.rms_m},
            {"num_points", f.num_points},
            {"holes", holes}};
}

reassembly::PlanarFace face_from(const json& j) {
    reassembly::PlanarFace f;
    f.id = j.at("id").get<int>();
    f.normal = vec(j.at("normal"));
    f.offset_m = j.at("offset_m").get<double>();
    f.centre_m = vec(j.at("centre_m"));
    f.width_axis = vec(j.at("width_axis"));
    f.height_axis = f.normal.cross(f.width_axis);
    f.width_m = j.at("width_m").get<double>();
    f.height_m = j.at("height_m").get<double>();
    f.area_m2 = j.at("area_m2").get<double>();
    f.roughness_per_m2 =
        j.at("roughness_per_m2").is_number() ? j["roughness_per_m2"].get<double>() : 0.0;
    f.rms_m = j.at("rms_m").get<double>();
    f.num_points = j.at("num_points").get<std::size_t>();
    for (const json& h : j.at("holes")) {
        reassembly::FaceHole hole{.kind = h.at("kind") == "dowel"
                                              ? reassembly::HoleKind::kDowel
                                              : reassembly::HoleKind::kClampChannel,
                                  .centre_m = vec(h.at("centre_m")),
                                  .face_uv_m = {h.at("face_uv_m").at(0).get<double>(),
                                                h.at("face_uv_m").at(1).get<double>()},
                                  .length_m = h.at("length_m").get<double>(),
                                  .width_m = h.at("width_m").get<double>(),
                                  .depth_m = h.at("depth_m").get<double>()};
        f.holes.push_back(hole);
    }
    return f;
}

constexpr BlockStatus kStatuses[] = {BlockStatus::kOk,          BlockStatus::kEmpty,
                                     BlockStatus::kNoNormals,   BlockStatus::kBadMesh,
                                     BlockStatus::kNonManifold, BlockStatus::kNoPlanarFace,
                                     BlockStatus::kTooFewFaces, BlockStatus::kTooNoisy};

}  // namespace

json to_json(const NamedBlockFeatures& block) {
    const reassembly::BlockFeatures& b = block.features;
    json faces = json::array(), edges = json::array();
    for (const auto& f : b.faces) faces.push_back(face_json(f));
    for (const auto& e : b.edges)
        edges.push_back({{"from", e.from},
                         {"to", e.to},
                         {"point_m", vec(e.point_m)},
                         {"direction", vec(e.direction)},
                         {"length_m", e.length_m},
                         {"angle_deg", e.angle_deg}});
    return {{"id", block.id},
            {"source", block.source},
            {"status", reassembly::to_string(b.status)},
            {"message", b.message},
            {"num_points", b.num_points},
            {"spacing_m", b.spacing_m},
            {"faces", faces},
            {"edges", edges}};
}

namespace {

// A string member or "" when absent (json::value trips GCC 12's -Wnull-dereference here).
std::string string_or_empty(const json& j, const char* key) {
    return j.contains(key) ? j.at(key).get<std::string>() : std::string();
}

}  // namespace

Expected<NamedBlockFeatures> block_features_from_json(const json& j,
                                                      const std::string& source_name) {
    try {
        NamedBlockFeatures out{.id = j.at("id").get<std::string>(),
                               .source = string_or_empty(j, "source")};
        reassembly::BlockFeatures& b = out.features;
        const std::string status = j.at("status").get<std::string>();
        const auto* s = std::find_if(std::begin(kStatuses), std::end(kStatuses),
                                     [&](BlockStatus x) { return status == to_string(x); });
        if (s == std::end(kStatuses))
            return fail(ErrorCode::kFormat, source_name + ": unknown status '" + status + "'");
        b.status = *s;
        b.message = string_or_empty(j, "message");
        b.num_points = j.at("num_points").get<std::size_t>();
        b.spacing_m = j.at("spacing_m").get<double>();
        for (const json& f : j.at("faces")) b.faces.push_back(face_from(f));
        for (const json& e : j.at("edges"))
            b.edges.push_back({.from = e.at("from").get<int>(),
                               .to = e.at("to").get<int>(),
                               .point_m = vec(e.at("point_m")),
                               .direction = vec(e.at("direction")),
                               .length_m = e.at("length_m").get<double>(),
                               .angle_deg = e.at("angle_deg").get<double>()});
        const int n = static_cast<int>(b.faces.size());
        for (const auto& e : b.edges)
            if (e.from < 0 || e.from >= n || e.to < 0 || e.to >= n)
                return fail(ErrorCode::kFormat, source_name + ": an edge names a missing face");
        return out;
    } catch (const json::exception& e) {
        return fail(ErrorCode::kFormat, source_name + ": " + e.what());
    }
}

std::string face_label(const std::vector<NamedBlockFeatures>& blocks, reassembly::FaceRef ref) {
    return blocks[ref.block].id + ":" + std::to_string(ref.face);
}

}  // namespace anascan::acquisition
