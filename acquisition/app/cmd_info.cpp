// anascan info FILE...: what a scan, pose or mesh file holds.
#include <cstdio>
#include <string>
#include <vector>

#include "anascan/processing/io/e57.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/ptx.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/io/text_points.hpp"
#include "anascan/processing/io/xf.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

std::string attribute_list(const PointCloud& c) {
    std::string s = "xyz";
    if (c.has_normals()) s += ", normals";
    if (c.has_colors()) s += ", colours";
    if (c.has_intensity()) s += ", intensity";
    if (c.has_confidence()) s += ", confidence";
    return s;
}

void print_cloud(const PointCloud& c) {
    const Bounds b = local_bounds(c);
    const Eigen::Vector3f e = b.extent();
    std::printf("  points: %zu (%s)\n", c.size(), attribute_list(c).c_str());
    std::printf("  extent: %.4f x %.4f x %.4f m\n", e.x(), e.y(), e.z());
    std::printf("  origin: %.4f %.4f %.4f m\n", c.origin_m.x(), c.origin_m.y(), c.origin_m.z());
}

void print_pose(const char* label, const Pose& T) {
    const Eigen::Vector3d t = T.translation();
    std::printf("  %s: rotation %.4f deg, translation %.6f %.6f %.6f m\n", label,
                rotation_angle_deg(T), t.x(), t.y(), t.z());
}

const char* format_name(io::PlyFormat f) {
    switch (f) {
        case io::PlyFormat::kAscii:
            return "ascii";
        case io::PlyFormat::kBinaryLittleEndian:
            return "binary little endian";
        case io::PlyFormat::kBinaryBigEndian:
            return "binary big endian";
    }
    return "?";
}

void info_ply(const std::filesystem::path& path) {
    auto ply = io::read_ply(path);
    if (!ply) fail_command(ply.error());
    std::printf("%s: PLY, %s\n", path.c_str(), format_name(ply->format));
    print_cloud(ply->cloud);
    if (!ply->triangles.empty()) std::printf("  triangles: %zu\n", ply->triangles.size());
    if (ply->grid)
        std::printf("  range grid: %d rows x %d columns\n", ply->grid->rows, ply->grid->cols);
    for (const std::string& e : ply->skipped_elements)
        std::printf("  skipped element: %s\n", e.c_str());
}

void info_ptx(const std::filesystem::path& path) {
    auto ptx = io::read_ptx(path);
    if (!ptx) fail_command(ptx.error());
    std::printf("%s: PTX, %zu station(s)\n", path.c_str(), ptx->size());
    for (const io::PtxScan& s : *ptx) {
        std::printf(" station %s: grid %d rows x %d columns\n", s.scan.meta.id.c_str(), s.grid.rows,
                    s.grid.cols);
        print_cloud(s.scan.cloud);
        if (s.scan.meta.T_world_scan) print_pose("pose", *s.scan.meta.T_world_scan);
    }
}

void info_e57(const std::filesystem::path& path) {
    auto e57 = io::read_e57(path);
    if (!e57) fail_command(e57.error());
    std::printf("%s: E57, %zu scan(s), %zu image(s) (not read)\n", path.c_str(), e57->scans.size(),
                e57->image_count);
    for (const io::E57Scan& s : e57->scans) {
        std::printf(" scan %s '%s': %llu records, %llu invalid\n", s.scan.meta.id.c_str(),
                    s.name.c_str(), static_cast<unsigned long long>(s.record_count),
                    static_cast<unsigned long long>(s.invalid_count));
        if (s.grid.rows > 0)
            std::printf("  grid: %d rows x %d columns\n", s.grid.rows, s.grid.cols);
        print_cloud(s.scan.cloud);
        if (s.scan.meta.T_world_scan) {
            print_pose("pose", *s.scan.meta.T_world_scan);
        } else {
            std::printf("  pose: none (scan frame = file frame)\n");
        }
    }
}

void info_conf(const std::filesystem::path& path) {
    auto conf = io::read_conf(path);
    if (!conf) fail_command(conf.error());
    std::printf("%s: Stanford .conf, %zu scan(s)\n", path.c_str(), conf->entries.size());
    for (const io::ConfEntry& e : conf->entries) print_pose(e.file.c_str(), e.T_world_scan);
}

void info_file(const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".ply") return info_ply(path);
    if (ext == ".ptx") return info_ptx(path);
    if (ext == ".e57") return info_e57(path);
    if (ext == ".conf") return info_conf(path);
    if (ext == ".xf") {
        auto T = io::read_xf(path);
        if (!T) fail_command(T.error());
        std::printf("%s: 4x4 transform\n", path.c_str());
        return print_pose("pose", *T);
    }
    auto cloud = io::read_text_points(path);
    if (!cloud) fail_command(cloud.error());
    std::printf("%s: text points\n", path.c_str());
    print_cloud(*cloud);
}

}  // namespace

void add_info_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "info", "Describe scan, mesh and pose files (.ply .xyz .pts .ptx .e57 .conf .xf)");
    auto files = std::make_shared<std::vector<std::string>>();
    cmd->add_option("files", *files, "Files to describe")->required()->check(CLI::ExistingFile);
    cmd->callback([files] {
        for (const std::string& f : *files) info_file(f);
    });
}

}  // namespace anascan::cli
