// assembly.json (status, poses, per-iteration residuals, the dense check) and the table.
#include "assembly_report.hpp"

#include <cstdio>

namespace anascan::cli {

namespace ra = anascan::reassembly;
using nlohmann::json;

namespace {

json pose_rows(const Pose& T) {
    json rows = json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
    return rows;
}

json check_json(const ra::AssemblyCheck& c) {
    json contacts = json::array(), coplanar = json::array(), colinear = json::array();
    for (const auto& x : c.contacts)
        contacts.push_back({{"pair", x.pair},
                            {"points", x.points},
                            {"gap_median_mm", 1e3 * x.gap_median_m},
                            {"gap_p95_mm", 1e3 * x.gap_p95_m},
                            {"gap_max_mm", 1e3 * x.gap_max_m},
                            {"gap_min_mm", 1e3 * x.gap_min_m}});
    for (const auto& x : c.coplanar)
        coplanar.push_back(
            {{"pair", x.pair}, {"angle_deg", x.angle_deg}, {"offset_mm", 1e3 * x.offset_m}});
    for (const auto& x : c.colinear)
        colinear.push_back(
            {{"pair", x.pair}, {"angle_deg", x.angle_deg}, {"distance_mm", 1e3 * x.distance_m}});
    return {{"penetration_max_mm", 1e3 * c.penetration_max_m},
            {"penetration_mean_mm", 1e3 * c.penetration_mean_m},
            {"penetrating_points", c.penetrating_points},
            {"measured_points", c.measured_points},
            {"contacts", contacts},
            {"coplanar", coplanar},
            {"colinear", colinear}};
}

}  // namespace

json assembly_report_json(const ra::AssemblyProblem& p, const ra::AssemblyResult& r,
                          const ra::AssemblyCheck& check, double seconds) {
    json blocks = json::array(), history = json::array();
    for (std::size_t b = 0; b < p.blocks.size(); ++b)
        blocks.push_back({{"id", p.blocks[b].id},
                          {"fixed", std::count(p.fixed.begin(), p.fixed.end(), int(b)) > 0 ||
                                        (p.fixed.empty() && b == 0)},
                          {"T_assembly_model", pose_rows(r.T_world_block[b])}});
    for (const auto& h : r.history)
        history.push_back({{"registration_rms_mm", 1e3 * h.registration_rms_m},
                           {"coplanar_rms_mm", 1e3 * h.coplanar_rms_m},
                           {"colinear_rms_mm", 1e3 * h.colinear_rms_m},
                           {"constraint_samples", h.constraint_samples},
                           {"active_constraints", h.active_constraints}});
    return {{"status", ra::to_string(r.status)},
            {"message", r.message},
            {"offending", r.offending},
            {"iterations", r.iterations},
            {"seconds", seconds},
            {"blocks", blocks},
            {"history", history},
            {"check", check_json(check)}};
}

void print_assembly_report(const ra::AssemblyProblem& p, const ra::AssemblyResult& r,
                           const ra::AssemblyCheck& c) {
    std::printf("%zu blocks, %zu pairs, %zu co-planar, %zu co-linear: %s after %d iterations%s%s\n",
                p.blocks.size(), p.contacts.size(), p.coplanar.size(), p.colinear.size(),
                ra::to_string(r.status), r.iterations, r.message.empty() ? "" : ": ",
                r.message.c_str());
    if (!r.history.empty()) {
        const auto& h = r.history.back();
        std::printf(
            "residuals (last iteration): registration %.3f mm, co-planar %.3f mm, co-linear %.3f "
            "mm; "
            "%zu constraint samples, %zu active\n",
            1e3 * h.registration_rms_m, 1e3 * h.coplanar_rms_m, 1e3 * h.colinear_rms_m,
            h.constraint_samples, h.active_constraints);
    }
    std::printf(
        "penetration on the dense models: max %.3f mm, mean %.3f mm over %zu of %zu points\n",
        1e3 * c.penetration_max_m, 1e3 * c.penetration_mean_m, c.penetrating_points,
        c.measured_points);
    for (const auto& x : c.contacts)
        std::printf(
            "pair %-20s gap median %.2f mm, p95 %.2f mm, max %.2f mm, min %.2f mm (%zu points)\n",
            x.pair.c_str(), 1e3 * x.gap_median_m, 1e3 * x.gap_p95_m, 1e3 * x.gap_max_m,
            1e3 * x.gap_min_m, x.points);
    for (const auto& x : c.coplanar)
        std::printf("co-planar %-15s %.3f deg, %.2f mm\n", x.pair.c_str(), x.angle_deg,
                    1e3 * x.offset_m);
    for (const auto& x : c.colinear)
        std::printf("co-linear %-15s %.3f deg, %.2f mm\n", x.pair.c_str(), x.angle_deg,
                    1e3 * x.distance_m);
    for (const auto& x : r.offending) std::printf("offending: %s\n", x.c_str());
}

}  // namespace anascan::cli
