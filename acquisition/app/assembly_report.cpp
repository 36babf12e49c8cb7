// The table of `blocks assemble`: status, residuals, the dense check.
#include "assembly_report.hpp"

#include <cstdio>

namespace anascan::cli {

namespace ra = anascan::reassembly;

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
