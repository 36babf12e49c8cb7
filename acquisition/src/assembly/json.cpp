#include <nlohmann/json.hpp>

#include "anascan/acquisition/assembly/assembly.hpp"

namespace anascan::acquisition {

std::string report_to_json(const AssemblyReport& report) {
    nlohmann::json scans = nlohmann::json::array();
    for (const AssembledScan& s : report.scans) {
        scans.push_back(
            {{"file", s.file}, {"points", s.points}, {"non_finite_removed", s.non_finite_removed}});
    }
    nlohmann::json pairs = nlohmann::json::array();
    for (const PairReport& p : report.pairs) {
        pairs.push_back({{"a", p.a},
                         {"b", p.b},
                         {"overlap_fraction", p.agreement.overlap_fraction},
                         {"median_distance_m", p.agreement.median_distance_m},
                         {"rms_distance_m", p.agreement.rms_distance_m},
                         {"samples", p.agreement.samples}});
    }
    const nlohmann::json doc = {{"scans", scans},
                                {"pairs", pairs},
                                {"model_points", report.model.size()},
                                {"median_pair_distance_m", report.median_pair_distance_m},
                                {"worst_pair_distance_m", report.worst_pair_distance_m}};
    return doc.dump(2);
}

}  // namespace anascan::acquisition
