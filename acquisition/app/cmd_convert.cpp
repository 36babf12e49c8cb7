// anascan convert IN OUT: any supported point format to PLY or XYZ text (by OUT's extension).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <map>
#include <vector>

#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/ptx.hpp"
#include "anascan/processing/io/text_points.hpp"
#include "commands.hpp"
#include "point_files.hpp"

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
    check_point_input(in);
    std::vector<PointCloud> clouds;
    if (lower_extension(in) == ".ply") {
        auto ply = io::read_ply(in);
        if (!ply) fail_command(ply.error());
        clouds.push_back(std::move(ply->cloud));
    } else if (lower_extension(in) == ".ptx") {
        auto ptx = io::read_ptx(in);
        if (!ptx) fail_command(ptx.error());
        for (io::PtxScan& s : *ptx) {
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

void run_convert(const ConvertOptions& o) {
    check_point_output(o.output);
    check_output_writable(o.output, "output");
    std::vector<PointCloud> clouds = read_clouds(o);
    for (std::size_t i = 0; i < clouds.size(); ++i) {
        PointCloud& cloud = clouds[i];
        if (!o.keep_non_finite) {
            if (std::size_t n = remove_non_finite(cloud))
                spdlog::warn("dropped {} non-finite points", n);
        }
        const std::filesystem::path out = output_path(o, i, clouds.size());
        write_points(out, cloud, {.format = o.format});
        std::printf("wrote %s (%zu points)\n", out.c_str(), cloud.size());
    }
}

}  // namespace

void add_convert_command(CLI::App& app) {
    auto opts = std::make_shared<ConvertOptions>();
    auto* cmd = app.add_subcommand(
        "convert",
        "Convert .ply/.xyz/.pts/.ptx points to PLY or XYZ text, the format OUT's extension "
        "names (one file per PTX station: OUT-NN.ply)");
    cmd->add_option("input", opts->input, "Input file")->required()->check(CLI::ExistingFile);
    cmd->add_option("output", opts->output, "Output file (.ply, or .xyz/.txt/.asc for XYZ text)")
        ->required();
    const std::map<std::string, io::PlyFormat> formats{
        {"binary", io::PlyFormat::kBinaryLittleEndian},
        {"binary-be", io::PlyFormat::kBinaryBigEndian},
        {"ascii", io::PlyFormat::kAscii}};
    cmd->add_option("--format", opts->format, "PLY encoding (default binary little endian)")
        ->transform(CLI::CheckedTransformer(formats, CLI::ignore_case));
    cmd->add_flag("--keep-non-finite", opts->keep_non_finite,
                  "Keep NaN/inf points (default: drop)");
    cmd->add_flag("--world", opts->world_frame, "PTX: write points in the registered frame");
    cmd->callback([opts] { run_convert(*opts); });
}

}  // namespace anascan::cli
