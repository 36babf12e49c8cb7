// libFuzzer harness for the .xf reader: errors name the source and a line, and every
// successful parse survives format_xf -> parse_xf with the pose equal within 1e-9.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>

#include "anascan/processing/io/xf.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const char> bytes(reinterpret_cast<const char*>(data), size);
    const auto T = anascan::io::parse_xf(bytes, "fuzz.xf");
    if (!T) {
        if (T.error().message.rfind("fuzz.xf: line ", 0) != 0) std::abort();
        return 0;
    }
    const Eigen::Matrix3d R = T->linear();
    if (!(R.transpose() * R).isIdentity(1e-12) || !(R.determinant() > 0.0)) std::abort();
    const std::string text = anascan::io::format_xf(*T);
    const auto back = anascan::io::parse_xf(text, "formatted.xf");
    if (!back) std::abort();
    const double rotation = (back->linear() - T->linear()).cwiseAbs().maxCoeff();
    const double scale = std::max(1.0, T->translation().cwiseAbs().maxCoeff());
    const double translation = (back->translation() - T->translation()).cwiseAbs().maxCoeff();
    if (rotation > 1e-9 || translation > 1e-9 * scale) std::abort();
    return 0;
}
