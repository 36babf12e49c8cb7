// libFuzzer harness for the OBJ reader: any input gives either a mesh whose triangles index
// its vertices and whose attributes agree, or an error naming the source and a line.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "anascan/processing/io/mesh_formats.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const char> bytes(reinterpret_cast<const char*>(data), size);
    const auto mesh = anascan::io::parse_obj(bytes, "fuzz.obj");
    if (!mesh) {
        if (mesh.error().message.rfind("fuzz.obj: line ", 0) != 0) std::abort();
        return 0;
    }
    if (mesh->vertices.empty() || !mesh->vertices.attributes_consistent()) std::abort();
    for (const Eigen::Vector3f& p : mesh->vertices.positions) {
        if (!p.allFinite()) std::abort();
    }
    for (const Eigen::Vector3i& t : mesh->triangles) {
        for (int k = 0; k < 3; ++k) {
            if (t[k] < 0 || std::size_t(t[k]) >= mesh->vertices.size()) std::abort();
        }
    }
    const auto again = anascan::io::parse_obj(anascan::io::serialize_obj(*mesh), "again.obj");
    if (!again || again->triangles != mesh->triangles) std::abort();
    return 0;
}
