// The coverage samples as a coloured PLY (processing's io writer does the file work).

#include "anascan/processing/io/coverage_ply.hpp"

#include <cstdio>

#include "anascan/processing/io/ply.hpp"

namespace anascan::io {

Expected<void> write_coverage_ply(const std::filesystem::path& path, const CoverageReport& report) {
    if (report.samples.empty())
        return fail(ErrorCode::kEmpty, path.string() + ": coverage report has no samples (" +
                                           to_string(report.status) + ")");
    char fraction[96];
    std::snprintf(fraction, sizeof(fraction), "anascan coverage %.5f of %.6f m2", report.fraction,
                  report.surface_area_m2);
    PlyWriteOptions options;
    options.comments = {fraction, "anascan colours: green observed, yellow sparse, red unobserved"};
    return write_ply(path, report.samples, options);
}

}  // namespace anascan::io
