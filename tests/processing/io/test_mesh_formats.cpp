#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/mesh_formats.hpp"

namespace anascan::io {
namespace {

Mesh tetrahedron() {
    Mesh m;
    m.vertices.positions = {{0, 0, 0}, {0.1f, 0, 0}, {0, 0.1f, 0}, {0, 0, 0.1f}};
    m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return m;
}

std::span<const char> bytes_of(const std::string& s) { return {s.data(), s.size()}; }

void expect_same(const Mesh& a, const Mesh& b, float tolerance) {
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    ASSERT_EQ(a.triangles, b.triangles);
    for (std::size_t i = 0; i < a.vertices.size(); ++i) {
        EXPECT_LT((a.vertices.world_position(i) - b.vertices.world_position(i)).norm(), tolerance);
    }
}

// The same triangles corner by corner (STL renumbers vertices in order of appearance).
void expect_same_geometry(const Mesh& a, const Mesh& b, double tolerance) {
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    for (std::size_t t = 0; t < a.triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_LT((a.vertices.world_position(a.triangles[t][k]) -
                       b.vertices.world_position(b.triangles[t][k]))
                          .norm(),
                      tolerance);
        }
    }
}

TEST(MeshFormats, ObjRoundTripsWithNormals) {
    Mesh m = tetrahedron();
    m.vertices.normals.assign(4, Eigen::Vector3f::UnitZ());
    const std::vector<char> text = serialize_obj(m);
    auto back = parse_obj(text, "t.obj");
    ASSERT_TRUE(back) << back.error().message;
    expect_same(m, *back, 1e-7f);
    EXPECT_EQ(back->vertices.normals.size(), 4u);
}

TEST(MeshFormats, ObjReadsPolygonsAndRelativeIndices) {
    const std::string text =
        "# quad\nmtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 0.5 0.5 0.5\nvt 0 0\n"
        "o thing\nf 1/1 2/1 3/1 4/1\nf -4 -2 -1\n";
    auto m = parse_obj(bytes_of(text), "q.obj");
    ASSERT_TRUE(m) << m.error().message;
    EXPECT_EQ(m->vertices.size(), 4u);
    ASSERT_EQ(m->triangles.size(), 3u);
    EXPECT_EQ(m->triangles[2], Eigen::Vector3i(0, 2, 3));
    EXPECT_TRUE(m->vertices.normals.empty());
}

TEST(MeshFormats, ObjErrorsNameFileAndLine) {
    const struct {
        std::string text, expected;
    } cases[] = {
        {"v 0 0 0\nv 1 0 0\nf 1 2 3\n", "bad.obj: line 3: vertex index 3 out of range"},
        {"v 0 0\n", "bad.obj: line 1: expected 3 coordinates"},
        {"v 0 0 nan\n", "bad.obj: line 1"},
        // Found by fuzz_obj: a finite double that no float position about an origin holds.
        {"v 0 0 0\nv 2e61 0 0\n", "bad.obj: line 2: coordinate out of range"},
        {"v 0 0 0\nf 1 1\n", "bad.obj: line 2: a face needs 3 corners"},
        {"v 0 0 0\nf 0 1 1\n", "bad.obj: line 2: bad vertex index '0'"},
        {"v 0 0 0\nf 1//7 1 1\n", "bad.obj: line 2: normal index 7 out of range"},
        {"# nothing\n", "bad.obj: line 1: no vertices"},
    };
    for (const auto& c : cases) {
        auto m = parse_obj(bytes_of(c.text), "bad.obj");
        ASSERT_FALSE(m) << c.text;
        EXPECT_EQ(m.error().message.rfind(c.expected, 0), 0u) << m.error().message;
    }
}

TEST(MeshFormats, BinaryStlRoundTripsAndWelds) {
    const Mesh m = tetrahedron();
    const std::vector<char> bytes = serialize_stl(m);
    EXPECT_EQ(bytes.size(), 84u + 4u * 50u);
    auto back = parse_stl(bytes, "t.stl");
    ASSERT_TRUE(back) << back.error().message;
    expect_same_geometry(m, *back, 1e-7);
}

TEST(MeshFormats, AsciiStlIsRead) {
    const std::string text =
        "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
        "   vertex 0 1 0\n  endloop\n endfacet\n facet normal 0 0 1\n  outer loop\n"
        "   vertex 1 0 0\n   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid t\n";
    auto m = parse_stl(bytes_of(text), "a.stl");
    ASSERT_TRUE(m) << m.error().message;
    EXPECT_EQ(m->vertices.size(), 4u);
    EXPECT_EQ(m->triangles.size(), 2u);
}

TEST(MeshFormats, StlLiesAndDamageAreErrors) {
    std::vector<char> bytes = serialize_stl(tetrahedron());
    std::vector<char> lying = bytes;
    const std::uint32_t big = 1000000;
    std::memcpy(lying.data() + 80, &big, 4);
    auto m = parse_stl(lying, "lie.stl");
    ASSERT_FALSE(m);
    EXPECT_EQ(m.error().code, ErrorCode::kTruncated);
    EXPECT_NE(m.error().message.find("lie.stl: byte 80: binary STL announces 1000000"),
              std::string::npos);
    std::vector<char> nan = bytes;
    const float bad = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(nan.data() + 84 + 12, &bad, 4);
    auto n = parse_stl(nan, "nan.stl");
    ASSERT_FALSE(n);
    EXPECT_EQ(n.error().message.rfind("nan.stl: byte 96: triangle 0 of 4", 0), 0u);
    const std::string cut = "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n";
    auto c = parse_stl(bytes_of(cut), "cut.stl");
    ASSERT_FALSE(c);
    EXPECT_EQ(c.error().code, ErrorCode::kTruncated);
    EXPECT_EQ(c.error().message.rfind("cut.stl: line 4:", 0), 0u) << c.error().message;
    auto tiny = parse_stl(bytes_of("abc"), "tiny.stl");
    ASSERT_FALSE(tiny);
    EXPECT_EQ(tiny.error().message.rfind("tiny.stl: byte 0:", 0), 0u);
}

TEST(MeshFormats, ReadAndWriteByExtension) {
    const auto dir = std::filesystem::temp_directory_path() / "anascan_mesh_formats";
    std::filesystem::create_directories(dir);
    const Mesh m = tetrahedron();
    for (const char* name : {"t.ply", "t.obj", "t.STL"}) {
        ASSERT_TRUE(write_mesh(dir / name, m)) << name;
        auto back = read_mesh(dir / name);
        ASSERT_TRUE(back) << back.error().message;
        expect_same_geometry(m, *back, 1e-7);
    }
    auto unknown = write_mesh(dir / "t.off", m);
    ASSERT_FALSE(unknown);
    EXPECT_NE(unknown.error().message.find("t.off: unknown mesh format"), std::string::npos);
    Mesh broken = m;
    broken.triangles.push_back({0, 1, 9});
    EXPECT_FALSE(write_mesh(dir / "b.obj", broken));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace anascan::io
