// anascan convert IN OUT: any supported point format to PLY, or to E57 (OUT.e57).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <map>
#include <vector>

#include "anascan/processing/io/e57.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/ptx.hpp"
#include "anascan/processing/io/text_points.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

struct ConvertOptions {
    std::string input;
    std::string output;
    io::PlyFormat format = io::PlyFormat::kBinaryLittleEndian;
    bool keep_non_finite = false;
    bool world_frame = false;
};

std::vector<PointCloud> read_clouds(const ConvertOptions& o) {
    const std::filesystem::path in(o.input);
    std::vector<PointCloud> clouds;
    if (in.extension() == ".ply") {
        auto ply = io::read_ply(in);
        if (!ply) fail_command(ply.error());
        clouds.push_back(std::move(ply->cloud));
    } else if (in.extension() == ".ptx") {
        auto ptx = io::read_ptx(in);
        if (!ptx) fail_command(ptx.error());
        for (io::PtxScan& s : *ptx) {
            const Pose T = s.scan.meta.T_world_scan.value_or(Pose::Identity());
            clouds.push_back(o.world_frame ? transformed(s.scan.cloud, T)
                                           : std::move(s.scan.cloud));
        }
    } else if (in.extension() == ".e57") {
        auto e57 = io::read_e57(in);
        if (!e57) fail_command(e57.error());
        for (io::E57Scan& s : e57->scans) {
            const Pose T = s.scan.meta.T_world_scan.value_or(Pose::Identity());
            clouds.push_back(o.world_frame ? transformed(s.scan.cloud, T)
                                           : std::move(s.scan.cloud));
        }
    } else {
        auto cloud = io::read_text_points(in);
        if (!cloud) fail_command(cloud.error());
        clouds.push_back(std::move(*cloud));
    }
    return clouds;
}

std::filesystem::path output_path(const ConvertOptions& o, std::size_t index, std::size_t count) {
    std::filesystem::path out(o.output);
    if (count == 1) return out;
    char suffix[32];
    std::snprintf(suffix, sizeof suffix, "-%02zu", index);
    return out.parent_path() / (out.stem().string() + suffix + out.extension().string());
}

// The scans of IN with their grids and poses, for an E57 output.
std::vector<io::E57Scan> read_scans(const ConvertOptions& o) {
    const std::filesystem::path in(o.input);
    if (in.extension() == ".e57") {
        auto e57 = io::read_e57(in);
        if (!e57) fail_command(e57.error());
        return std::move(e57->scans);
    }
    std::vector<io::E57Scan> scans;
    if (in.extension() == ".ptx") {
        auto ptx = io::read_ptx(in);
        if (!ptx) fail_command(ptx.error());
        for (io::PtxScan& s : *ptx)
            scans.push_back({.scan = std::move(s.scan), .grid = std::move(s.grid)});
        return scans;
    }
    for (PointCloud& cloud : read_clouds(o)) scans.push_back({.scan = {.cloud = std::move(cloud)}});
    return scans;
}

void convert_to_e57(const ConvertOptions& o) {
    std::vector<io::E57Scan> scans = read_scans(o);
    for (std::size_t i = 0; i < scans.size(); ++i) {
        io::E57Scan& s = scans[i];
        if (s.name.empty())
            s.name = std::filesystem::path(o.input).stem().string() + "#" + std::to_string(i);
        if (s.grid.rows == 0 && !o.keep_non_finite) remove_non_finite(s.scan.cloud);
    }
    if (auto ok = io::write_e57(o.output, scans); !ok) fail_command(ok.error());
    std::printf("wrote %s (%zu scan(s))\n", o.output.c_str(), scans.size());
}

void run_convert(const ConvertOptions& o) {
    if (std::filesystem::path(o.output).extension() == ".e57") return convert_to_e57(o);
    std::vector<PointCloud> clouds = read_clouds(o);
    for (std::size_t i = 0; i < clouds.size(); ++i) {
        PointCloud& cloud = clouds[i];
        if (!o.keep_non_finite) {
            if (std::size_t n = remove_non_finite(cloud))
                spdlog::warn("dropped {} non-finite points", n);
        }
        const std::filesystem::path out = output_path(o, i, clouds.size());
        if (auto ok = io::write_ply(out, cloud, {.format = o.format}); !ok)
            fail_command(ok.error());
        std::printf("wrote %s (%zu points)\n", out.c_str(), cloud.size());
    }
}

}  // namespace

void add_convert_command(CLI::App& app) {
    auto opts = std::make_shared<ConvertOptions>();
    auto* cmd = app.add_subcommand(
        "convert",
        "Convert .ply/.xyz/.pts/.ptx/.e57 points to PLY (one file per station: OUT-NN.ply) "
        "or to one E57 file (OUT.e57, grids and poses kept)");
    cmd->add_option("input", opts->input, "Input file")->required()->check(CLI::ExistingFile);
    cmd->add_option("output", opts->output, "Output .ply or .e57 file")->required();
    const std::map<std::string, io::PlyFormat> formats{
        {"binary", io::PlyFormat::kBinaryLittleEndian},
        {"binary-be", io::PlyFormat::kBinaryBigEndian},
        {"ascii", io::PlyFormat::kAscii}};
    cmd->add_option("--format", opts->format, "PLY encoding (default binary little endian)")
        ->transform(CLI::CheckedTransformer(formats, CLI::ignore_case));
    cmd->add_flag("--keep-non-finite", opts->keep_non_finite,
                  "Keep NaN/inf points (default: drop)");
    cmd->add_flag("--world", opts->world_frame,
                  "PTX/E57 to PLY: write points in the registered frame");
    cmd->callback([opts] { run_convert(*opts); });
}

}  // namespace anascan::cli
