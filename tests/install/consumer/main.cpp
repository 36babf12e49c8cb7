// A program outside the anascan tree using the installed package.
#include <anascan/processing/io/ply.hpp>
#include <anascan/processing/spatial/voxel_grid.hpp>

int main() {
    anascan::PointCloud cloud;
    cloud.positions = {{0.f, 0.f, 0.f}, {0.0001f, 0.f, 0.f}, {1.f, 1.f, 1.f}};
    const anascan::PointCloud reduced = anascan::voxel_downsample(cloud, {.voxel_size_m = 0.01});
    const std::vector<char> bytes = anascan::io::serialize_ply(reduced, {}, {});
    auto back = anascan::io::parse_ply(bytes, "memory");
    return back.has_value() && back->cloud.size() == 2 ? 0 : 1;
}
