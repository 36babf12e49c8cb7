// campaign_status: the stages' counts and the scans not used or not placed, from the store.
#include "anascan/acquisition/campaign/campaign_results.hpp"
#include "campaign/campaign_json.hpp"

namespace anascan::acquisition {
namespace {

void count_scans(const std::vector<CampaignScanRow>& scans, CampaignStatus& c) {
    for (const CampaignScanRow& s : scans) {
        ++c.scans;
        c.prepared += s.state == "prepared" || s.state == "described";
        c.described += s.state == "described";
        c.unusable += s.state == "unusable";
        if (s.state == "unusable") c.problems.push_back("not used: " + s.file + ": " + s.problem);
    }
}

Expected<void> count_pairs(const CampaignStore& store, CampaignStatus& c) {
    auto pairs = store.pairs();
    if (!pairs) return fail(pairs.error());
    for (const CampaignPairRow& p : *pairs) {
        ++c.pairs;
        if (p.result_json.empty()) continue;
        auto result = read_pair_result(p.result_json);
        if (!result) {
            return fail(campaign_json::damaged(
                store, "pair " + std::to_string(p.source) + "-" + std::to_string(p.target),
                result.error()));
        }
        ++c.registered;
        c.verified += *result && (*result)->verified;
    }
    return {};
}

void stone_problems(const std::vector<CampaignScanRow>& scans, std::int64_t stone,
                    const CampaignStoneResult& result, std::vector<std::string>& problems) {
    const std::string where = " (stone " + std::to_string(stone) + "): ";
    for (const CampaignStoneScan& s : result.scans) {
        const std::string& file = scans[static_cast<std::size_t>(s.id)].file;
        if (!s.placed) problems.push_back("not placed" + where + file + ": " + s.reason);
        if (!s.warning.empty()) problems.push_back("warning" + where + file + ": " + s.warning);
    }
}

Expected<void> count_stones(const CampaignStore& store, const std::vector<CampaignScanRow>& scans,
                            CampaignStatus& c) {
    auto stones = store.stones();
    if (!stones) return fail(stones.error());
    for (const CampaignStoneRow& stone : *stones) {
        ++c.stones;
        if (stone.result_json.empty()) continue;
        auto result = read_stone_result(stone.result_json, scans.size());
        if (!result) {
            return fail(
                campaign_json::damaged(store, "stone " + std::to_string(stone.id), result.error()));
        }
        ++c.stones_done;
        c.placed += result->placed;
        stone_problems(scans, stone.id, *result, c.problems);
    }
    return {};
}

}  // namespace

Expected<CampaignStatus> campaign_status(const CampaignStore& store) {
    CampaignStatus c;
    auto scans = store.scans();
    if (!scans) return fail(scans.error());
    count_scans(*scans, c);
    if (auto ok = count_pairs(store, c); !ok) return fail(ok.error());
    if (auto ok = count_stones(store, *scans, c); !ok) return fail(ok.error());
    return c;
}

}  // namespace anascan::acquisition
