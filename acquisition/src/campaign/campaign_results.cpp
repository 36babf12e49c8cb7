// The campaign's stored results, read back checked, and the status built on them.
#include "anascan/acquisition/campaign/campaign_results.hpp"

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "campaign/campaign_json.hpp"

namespace anascan::acquisition {
namespace {

using nlohmann::json;

struct Damaged : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void require(bool ok, const std::string& problem) {
    if (!ok) throw Damaged(problem);
}

/// Runs `read` on the parsed text; a parse error, a value of the wrong type (nlohmann throws
/// both) or a failed `require` becomes a kFormat error naming `what`.
template <class Read>
auto guarded(const std::string& text, const std::string& what, Read&& read)
    -> Expected<decltype(read(json()))> {
    try {
        return read(json::parse(text));
    } catch (const json::exception& e) {
        return fail(ErrorCode::kFormat, what + " is damaged (" + e.what() + ")");
    } catch (const Damaged& e) {
        return fail(ErrorCode::kFormat, what + " is damaged (" + e.what() + ")");
    }
}

/// nlohmann converts a JSON float to an integer with a static_cast (undefined out of range):
/// the integers are checked to be JSON integers first.
void require_whole(const json& object, const char* key) {
    require(!object.contains(key) || object[key].is_number_integer(),
            std::string(key) + " is not a whole number");
}

std::int64_t scan_id(const json& j, std::size_t scan_count) {
    require(j.is_number_integer(), "a scan id is not a whole number");
    const auto id = j.get<std::int64_t>();
    require(id >= 0 && static_cast<std::size_t>(id) < scan_count,
            "names scan " + std::to_string(id) + " of " + std::to_string(scan_count));
    return id;
}

Pose stored_pose(const json& rows) {
    require(rows.is_array() && rows.size() == 16, "a pose is 16 numbers");
    Pose T = campaign_json::pose_from(rows);
    for (int i = 0; i < 16; ++i)
        require(std::isfinite(rows[std::size_t(i)].get<double>()),
                "a pose holds a value that is not finite");
    return T;
}

CampaignStoneScan stone_scan(const json& j, std::size_t scan_count) {
    return {.id = scan_id(j.at("id"), scan_count),
            .placed = j.at("placed").get<bool>(),
            .T_stone_scan = stored_pose(j.at("pose")),
            .reason = j.at("reason").get<std::string>(),
            .warning = j.at("warning").get<std::string>()};
}

}  // namespace

Expected<PreparedSummary> read_scan_summary(const std::string& text) {
    if (text.empty()) return PreparedSummary{};
    return guarded(text, "the prepared summary", [](const json& j) {
        require(j.is_object(), "not an object");
        for (const char* key : {"points", "position_hash"}) require_whole(j, key);
        PreparedSummary s = campaign_json::summary_from(j);
        require(std::isfinite(s.spacing_m) && s.spacing_m >= 0 && std::isfinite(s.diagonal_m) &&
                    s.centre_m.allFinite(),
                "a spacing, size or centre is not a finite length");
        return s;
    });
}

Expected<std::optional<CampaignPairResult>> read_pair_result(const std::string& text) {
    return guarded(text, "the pair's result", [](const json& j) {
        require(j.is_object(), "not an object");
        if (j.contains("error")) {
            j.at("error").get<std::string>();
            return std::optional<CampaignPairResult>();
        }
        require_whole(j, "status_code");
        if (j.contains("T_target_source")) stored_pose(j.at("T_target_source"));
        return std::optional<CampaignPairResult>(campaign_json::pair_from(j));
    });
}

Expected<CampaignStoneResult> read_stone_result(const std::string& text, std::size_t scan_count) {
    return guarded(text, "the stone's result", [scan_count](const json& j) {
        require(j.is_object(), "not an object");
        CampaignStoneResult r;
        if (j.contains("error")) return r;  // The task failed; nothing placed.
        for (const json& scan : j.at("scans")) r.scans.push_back(stone_scan(scan, scan_count));
        for (const CampaignStoneScan& s : r.scans) r.placed += s.placed;
        return r;
    });
}

Expected<std::map<std::int64_t, std::string>> read_graph_warnings(const std::string& text,
                                                                  std::size_t scan_count) {
    if (text.empty()) return std::map<std::int64_t, std::string>{};
    return guarded(text, "the match graph", [scan_count](const json& j) {
        require(j.is_object(), "not an object");
        std::map<std::int64_t, std::string> out;
        const json warnings = j.value("warnings", json::object());
        for (const auto& [key, warning] : warnings.items()) {
            char* end = nullptr;
            const long long id = std::strtoll(key.c_str(), &end, 10);
            require(end != key.c_str() && *end == '\0', "warning key '" + key + "'");
            out[scan_id(json(id), scan_count)] = warning.get<std::string>();
        }
        return out;
    });
}

namespace campaign_json {

Expected<void> verify_stored(const CampaignStore& store,
                             const std::vector<CampaignScanRow>& scans) {
    for (const CampaignScanRow& scan : scans) {
        if (auto ok = read_scan_summary(scan.summary_json); !ok)
            return fail(damaged(store, "scan " + std::to_string(scan.id), ok.error()));
    }
    auto pairs = store.pairs();
    if (!pairs) return fail(pairs.error());
    for (const CampaignPairRow& p : *pairs) {
        if (p.result_json.empty()) continue;
        if (auto ok = read_pair_result(p.result_json); !ok) {
            return fail(damaged(store,
                                "pair " + std::to_string(p.source) + "-" + std::to_string(p.target),
                                ok.error()));
        }
    }
    auto stones = store.stones();
    if (!stones) return fail(stones.error());
    for (const CampaignStoneRow& stone : *stones) {
        if (stone.result_json.empty()) continue;
        if (auto ok = read_stone_result(stone.result_json, scans.size()); !ok)
            return fail(damaged(store, "stone " + std::to_string(stone.id), ok.error()));
    }
    auto graph = store.value("graph");
    if (!graph) return fail(graph.error());
    if (auto ok = read_graph_warnings(graph->value_or(""), scans.size()); !ok)
        return fail(damaged(store, "", ok.error()));
    return {};
}

}  // namespace campaign_json
}  // namespace anascan::acquisition
