#include "anascan/acquisition/store/session_json.hpp"

#include <array>
#include <ctime>
#include <nlohmann/json.hpp>

#include "anascan/acquisition/store/session_truth.hpp"

namespace anascan::acquisition {
namespace {

using nlohmann::json;

/// Simulated sessions: each scan of the model against its true pose (frame of the model's
/// first scan, translation at the scan's centroid); the scans off by more than 1° or 5 mm
/// are the model's wrong placements (flagged and failed scans are not in the model).
Expected<json> truth_json(const SessionStore& store) {
    auto truth = evaluate_session_truth(store);
    if (!truth) return fail(truth.error());
    if (!*truth) return json(nullptr);
    const PoseEvaluation& e = **truth;
    json scans = json::array();
    std::size_t wrong = 0;
    for (const ScanPoseError& s : e.scans) {
        if (!s.placed) continue;
        const bool off = s.rotation_deg > 1.0 || s.translation_m > 0.005;
        wrong += off;
        scans.push_back({{"seq", std::stoll(s.name)},
                         {"rotation_deg", s.rotation_deg},
                         {"translation_m", s.translation_m},
                         {"off", off}});
    }
    return json{{"reference_seq", std::stoll(e.reference)},
                {"model_scans", e.placed},
                {"max_rotation_deg", e.max_rotation_deg},
                {"max_translation_m", e.max_translation_m},
                {"off_1deg_5mm", wrong},
                {"scans", scans}};
}

json pose_json(const std::optional<Pose>& T) {
    if (!T) return nullptr;
    json values = json::array();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) values.push_back(T->matrix()(r, c));
    return values;
}

json object_or_null(const std::string& text) {
    if (text.empty()) return nullptr;
    json parsed = json::parse(text, nullptr, false);
    return parsed.is_discarded() ? json(text) : parsed;
}

json scan_json(const ScanRecord& r) {
    return {{"seq", r.seq},
            {"file", r.file},
            {"state", std::string(to_string(r.state))},
            {"group", r.group},
            {"pose", pose_json(r.pose)},
            {"true_pose", pose_json(r.true_pose)},
            {"latency_s", r.latency_s ? json(*r.latency_s) : json(nullptr)},
            {"excluded", r.excluded},
            {"device_id", r.device_id},
            {"device_kind", to_string(r.device_kind)},
            {"points", r.point_count},
            {"captured_at", format_utc(r.captured_at)},
            {"turned_over_before", r.turned_over_before},
            {"file_problem", r.file_problem},
            {"quality", object_or_null(r.quality_json)}};
}

}  // namespace

std::string format_utc(TimePoint t) {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(t.time_since_epoch());
    const std::time_t seconds = static_cast<std::time_t>(ms.count() / 1000);
    std::tm tm{};
    gmtime_r(&seconds, &tm);
    std::array<char, 40> text{};
    const std::size_t n = std::strftime(text.data(), text.size(), "%Y-%m-%dT%H:%M:%S", &tm);
    std::snprintf(text.data() + n, text.size() - n, ".%03dZ",
                  static_cast<int>(((ms.count() % 1000) + 1000) % 1000));
    return text.data();
}

Expected<std::optional<double>> coverage_fraction(const SessionStore& store) {
    auto value = store.value("coverage");
    if (!value) return fail(value.error());
    if (!*value) return std::optional<double>();
    const json parsed = json::parse(**value, nullptr, false);
    if (parsed.is_object() && parsed.contains("fraction") && parsed["fraction"].is_number()) {
        return std::optional<double>(parsed["fraction"].get<double>());
    }
    if (parsed.is_number()) return std::optional<double>(parsed.get<double>());
    return std::optional<double>();
}

Expected<std::string> session_info_json(const SessionStore& store, int indent) {
    auto scans = store.scans();
    auto devices = store.devices();
    auto events = store.events();
    auto notes = store.notes();
    auto coverage = coverage_fraction(store);
    auto coverage_report = store.value("coverage");
    if (!scans) return fail(scans.error());
    if (!devices) return fail(devices.error());
    if (!events) return fail(events.error());
    if (!notes) return fail(notes.error());
    if (!coverage) return fail(coverage.error());
    if (!coverage_report) return fail(coverage_report.error());
    json doc = {{"session", store.dir().string()}, {"schema_version", kSessionSchemaVersion}};
    doc["scans"] = json::array();
    for (const ScanRecord& r : *scans) doc["scans"].push_back(scan_json(r));
    doc["coverage"] = *coverage ? json(**coverage) : json(nullptr);
    doc["coverage_report"] = *coverage_report ? object_or_null(**coverage_report) : json(nullptr);
    doc["devices"] = json::array();
    for (const DeviceRecord& d : *devices) {
        doc["devices"].push_back(
            {{"id", d.id}, {"kind", to_string(d.kind)}, {"first_seen", format_utc(d.first_seen)}});
    }
    doc["events"] = events->size();
    auto truth = truth_json(store);
    if (!truth) return fail(truth.error());
    doc["truth"] = *truth;
    doc["notes"] = json::array();
    for (const SessionNote& n : *notes) {
        doc["notes"].push_back({{"seq", n.seq ? json(*n.seq) : json(nullptr)},
                                {"text", n.text},
                                {"time", format_utc(n.time)}});
    }
    // Text from the database (device ids, notes, events) need not be valid UTF-8.
    return doc.dump(indent, ' ', false, json::error_handler_t::replace);
}

}  // namespace anascan::acquisition
