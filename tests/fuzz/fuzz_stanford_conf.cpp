// libFuzzer harness for the Stanford .conf reader: errors name the source and a line, and
// every successful parse survives format_conf -> parse_conf with poses equal within 1e-9.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>

#include "anascan/processing/io/stanford_conf.hpp"

namespace {

// Rotation entries absolutely, translations relative to their size.
bool same_pose(const anascan::Pose& a, const anascan::Pose& b) {
    const double rotation = (a.linear() - b.linear()).cwiseAbs().maxCoeff();
    const double scale = std::max(1.0, a.translation().cwiseAbs().maxCoeff());
    const double translation = (a.translation() - b.translation()).cwiseAbs().maxCoeff();
    return rotation <= 1e-9 && translation <= 1e-9 * scale;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const char> bytes(reinterpret_cast<const char*>(data), size);
    const auto conf = anascan::io::parse_conf(bytes, "fuzz.conf");
    if (!conf) {
        if (conf.error().message.rfind("fuzz.conf: line ", 0) != 0) std::abort();
        return 0;
    }
    const std::string text = anascan::io::format_conf(*conf);
    const auto back = anascan::io::parse_conf(text, "formatted.conf");
    if (!back || back->entries.size() != conf->entries.size()) std::abort();
    if (back->camera.has_value() != conf->camera.has_value()) std::abort();
    if (conf->camera && !same_pose(*conf->camera, *back->camera)) std::abort();
    for (std::size_t i = 0; i < conf->entries.size(); ++i) {
        if (back->entries[i].file != conf->entries[i].file) std::abort();
        if (!same_pose(back->entries[i].T_world_scan, conf->entries[i].T_world_scan)) std::abort();
    }
    return 0;
}
