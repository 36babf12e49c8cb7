// Coverage report as JSON text (processing has no JSON library; the format is flat).

#include <cstdio>
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
    if (!report.message.empty()) {
        std::string message;  // escape quotes and backslashes (messages are our own text)
        for (char c : report.message) {
            if (c == '"' || c == '\\') message += '\\';
            message += c;
        }
        json += ", \"message\": \"" + message + "\"";
    }
    return json + "}";
}

}  // namespace anascan
