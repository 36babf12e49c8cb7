// libFuzzer harness for the STL reader (binary and ASCII): any input gives either a welded
// mesh with finite vertices that its triangles index, or an error naming the source and a
// byte offset or line.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "anascan/processing/io/mesh_formats.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const char> bytes(reinterpret_cast<const char*>(data), size);
    const auto mesh = anascan::io::parse_stl(bytes, "fuzz.stl");
    if (!mesh) {
        const std::string& m = mesh.error().message;
        if (m.rfind("fuzz.stl: byte ", 0) != 0 && m.rfind("fuzz.stl: line ", 0) != 0) std::abort();
        return 0;
    }
    if (mesh->triangles.empty()) std::abort();
    for (const Eigen::Vector3f& p : mesh->vertices.positions) {
        if (!p.allFinite()) std::abort();
    }
    for (const Eigen::Vector3i& t : mesh->triangles) {
        for (int k = 0; k < 3; ++k) {
            if (t[k] < 0 || std::size_t(t[k]) >= mesh->vertices.size()) std::abort();
        }
    }
    const auto again = anascan::io::parse_stl(anascan::io::serialize_stl(*mesh), "again.stl");
    if (!again || again->triangles.size() != mesh->triangles.size()) std::abort();
    return 0;
}
