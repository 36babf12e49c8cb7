// The coverage report as JSON: written for the session store and `coverage --json`, read
// back by the field app. One codec: the writer's keys are the reader's.

#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "anascan/processing/coverage/coverage.hpp"

namespace anascan {
namespace {

std::string vector_json(const Eigen::Vector3d& v, const char* format) {
    char text[128];
    std::snprintf(text, sizeof(text), format, v.x(), v.y(), v.z());
    return text;
}

std::string hole_json(const CoverageHole& hole) {
    char text[96];
    std::snprintf(text, sizeof(text), "{\"area_m2\": %.6f, \"sample_count\": %zu, ", hole.area_m2,
                  hole.sample_count);
    return text + std::string("\"centre_m\": ") + vector_json(hole.centre_m, "[%.5f, %.5f, %.5f]") +
           ", \"normal\": " + vector_json(hole.normal, "[%.4f, %.4f, %.4f]") + "}";
}

std::optional<double> number(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number()) return std::nullopt;
    return it->get<double>();
}

std::optional<Eigen::Vector3d> vector3(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_array() || it->size() != 3) return std::nullopt;
    for (const auto& v : *it)
        if (!v.is_number()) return std::nullopt;
    return Eigen::Vector3d((*it)[0].get<double>(), (*it)[1].get<double>(), (*it)[2].get<double>());
}

std::optional<CoverageHole> hole_from_json(const nlohmann::json& hole) {
    if (!hole.is_object()) return std::nullopt;
    const auto area = number(hole, "area_m2");
    const auto centre = vector3(hole, "centre_m");
    const auto normal = vector3(hole, "normal");
    if (!area || !centre || !normal) return std::nullopt;
    const auto samples = number(hole, "sample_count");
    return CoverageHole{.area_m2 = *area,
                        .centre_m = *centre,
                        .normal = *normal,
                        .sample_count = samples ? static_cast<std::size_t>(*samples) : 0};
}

std::optional<CoverageStatus> status_from_json(const nlohmann::json& doc) {
    const auto it = doc.find("status");
    if (it == doc.end() || !it->is_string()) return std::nullopt;
    for (const CoverageStatus s : {CoverageStatus::kOk, CoverageStatus::kNoScans,
                                   CoverageStatus::kNoStone, CoverageStatus::kInvalidSurface})
        if (*it == to_string(s)) return s;
    return std::nullopt;
}

}  // namespace

std::string coverage_to_json(const CoverageReport& report, std::size_t max_holes) {
    char text[320];
    std::snprintf(text, sizeof(text),
                  "{\"status\": \"%s\", \"fraction\": %.5f, \"surface_area_m2\": %.6f, "
                  "\"covered_area_m2\": %.6f, \"sparse_area_m2\": %.6f, \"hole_count\": %zu, ",
                  to_string(report.status), report.fraction, report.surface_area_m2,
                  report.covered_area_m2, report.sparse_area_m2, report.holes.size());
    std::string json = text;
    json += "\"holes\": [";
    for (std::size_t i = 0; i < report.holes.size() && i < max_holes; ++i)
        json += (i > 0 ? ", " : "") + hole_json(report.holes[i]);
    json += "]";
    if (!report.message.empty()) json += ", \"message\": " + nlohmann::json(report.message).dump();
    return json + "}";
}

Expected<CoverageSummary> coverage_from_json(std::string_view json) {
    const nlohmann::json doc = nlohmann::json::parse(json, nullptr, false);
    if (!doc.is_object()) return fail(ErrorCode::kFormat, "coverage JSON: not a JSON object");
    CoverageSummary out{.status = status_from_json(doc),
                        .fraction = number(doc, "fraction"),
                        .surface_area_m2 = number(doc, "surface_area_m2"),
                        .covered_area_m2 = number(doc, "covered_area_m2"),
                        .sparse_area_m2 = number(doc, "sparse_area_m2")};
    if (const auto count = number(doc, "hole_count"))
        out.hole_count = static_cast<std::size_t>(*count);
    if (const auto holes = doc.find("holes"); holes != doc.end() && holes->is_array()) {
        for (const auto& hole : *holes) {
            if (auto parsed = hole_from_json(hole)) {
                out.holes.push_back(*parsed);
            } else {
                ++out.malformed_holes;
            }
        }
    }
    if (const auto m = doc.find("message"); m != doc.end() && m->is_string()) out.message = *m;
    return out;
}

}  // namespace anascan
