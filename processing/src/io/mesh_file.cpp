// Reading and writing meshes by file extension.
#include <algorithm>
#include <cctype>
#include <string>

#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/mesh_formats.hpp"

namespace anascan::io {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

Unexpected<Error> unknown_extension(const std::filesystem::path& path) {
    return fail(ErrorCode::kUnsupported,
                path.string() + ": unknown mesh format (use .ply, .obj or .stl)");
}

Expected<void> check_indices(const std::filesystem::path& path, const Mesh& mesh) {
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const int v = mesh.triangles[t][k];
            if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size()) {
                return fail(ErrorCode::kInvalidArgument,
                            path.string() + ": cannot write: triangle " + std::to_string(t) +
                                " refers to vertex " + std::to_string(v) + " of " +
                                std::to_string(mesh.vertices.size()));
            }
        }
    }
    return {};
}

}  // namespace

Expected<Mesh> read_mesh(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext != ".ply" && ext != ".obj" && ext != ".stl") return unknown_extension(path);
    auto bytes = read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    const std::string name = path.string();
    if (ext == ".obj") return parse_obj(*bytes, name);
    if (ext == ".stl") return parse_stl(*bytes, name);
    auto ply = parse_ply(*bytes, name);
    if (!ply) return fail(ply.error());
    return Mesh{std::move(ply->cloud), std::move(ply->triangles)};
}

Expected<void> write_mesh(const std::filesystem::path& path, const Mesh& mesh,
                          const PlyWriteOptions& ply_options) {
    const std::string ext = lower_extension(path);
    if (ext == ".ply") return write_ply(path, mesh, ply_options);
    if (ext != ".obj" && ext != ".stl") return unknown_extension(path);
    if (auto ok = check_indices(path, mesh); !ok) return ok;
    return write_file_atomically(path, ext == ".obj" ? serialize_obj(mesh) : serialize_stl(mesh));
}

}  // namespace anascan::io
