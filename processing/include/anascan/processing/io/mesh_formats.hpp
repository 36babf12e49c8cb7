#pragma once
/// \file
/// Triangle-mesh exchange formats besides PLY: Wavefront OBJ (read and write) and STL
/// (binary read and write, ASCII read), and reading or writing a mesh by its extension.
///
/// Readers follow the point formats' hostile-input rules: every error names the source and
/// the line (text) or byte offset (binary), a count in a header is checked against the
/// bytes that follow before anything is allocated, non-finite coordinates and indices out
/// of range are errors, and no partial mesh is returned.

#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/io/ply.hpp"

namespace anascan::io {

/// Parses OBJ text: `v x y z` (extra w or colour fields ignored), `vn`, and `f` with
/// `i`, `i/t`, `i//n` or `i/t/n` corners (1-based or negative relative indices); polygons
/// are fan triangulated. Normals are kept when every vertex gets exactly one. Other
/// statements (vt, o, g, s, usemtl, mtllib, l, p) are ignored.
Expected<Mesh> parse_obj(std::span<const char> bytes, std::string_view source_name);

/// OBJ text: `v` lines with 9 significant digits in world coordinates, `vn` when the mesh
/// has normals, then `f` lines (with `i//i` corners when there are normals).
std::vector<char> serialize_obj(const Mesh& mesh);

/// Parses STL, binary (80-byte header, triangle count, 50 bytes per triangle) or ASCII
/// (`solid` ... `facet normal` / `outer loop` / 3 `vertex` / `endloop` / `endfacet`).
/// Corners with bit-identical coordinates become one vertex.
Expected<Mesh> parse_stl(std::span<const char> bytes, std::string_view source_name);

/// Binary STL: per-triangle normals from the winding, float world coordinates.
std::vector<char> serialize_stl(const Mesh& mesh);

/// Reads a mesh from .ply, .obj or .stl (by extension, case-insensitive).
Expected<Mesh> read_mesh(const std::filesystem::path& path);

/// Writes a mesh crash-safely as .ply (with `ply_options`), .obj or .stl.
Expected<void> write_mesh(const std::filesystem::path& path, const Mesh& mesh,
                          const PlyWriteOptions& ply_options = {});

}  // namespace anascan::io
