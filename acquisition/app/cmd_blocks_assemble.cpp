// anascan blocks assemble DIR --pair A:2=B:5 [--pair ...] [--coplanar A:1=B:3]
//   [--colinear A:1/4=B:3/0] [--fixed A] --out ASSEMBLY/   (or --proposals P.json --accepted)
// The penetration-free alignment of neighbouring blocks (method paper §5.3): DIR holds the
// ID.features.json of `blocks features`, whose models are read again; ASSEMBLY/ receives
// assembly.conf (one bmesh line per block), assembly.json (the report) and assembly.ply
// (the blocks coloured, penetrating points red).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <set>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/reassembly/assembly_check.hpp"
#include "assembly_report.hpp"
#include "block_features_json.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;
namespace ra = anascan::reassembly;
using nlohmann::json;

struct AssembleBlocksOptions {
    std::string dir, out, proposals;
    std::vector<std::string> pairs, coplanar, colinear, fixed;
    bool accepted = false;
    int max_iterations = 60;
    std::string joint_normal = "vertex";
};

// DIR's features files, sorted, and the block ids they name.
struct FeatureFiles {
    std::vector<fs::path> files;
    std::vector<std::string> ids;
    std::vector<std::size_t> face_counts;
};

FeatureFiles feature_files(const std::string& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        fail_command({ErrorCode::kIo, dir + ": not a folder of block features"});
    FeatureFiles out;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.path().string().ends_with(".features.json")) out.files.push_back(e.path());
    std::sort(out.files.begin(), out.files.end());
    if (out.files.empty())
        fail_command({ErrorCode::kIo, dir + ": no ID.features.json (run blocks features)"});
    for (const fs::path& f : out.files) {
        auto j = read_json_file(f);
        if (!j) fail_command(j.error());
        out.ids.push_back(j->value("id", f.stem().stem().string()));
        out.face_counts.push_back(j->value("faces", json::array()).size());
    }
    return out;
}

// The models of the features files (all read before any feature is found, so that a
// missing one fails at once), their features found again (deterministic).
void load_blocks(const FeatureFiles& in, ra::AssemblyProblem& p) {
    std::vector<Mesh> meshes;
    std::vector<std::string> sources;
    for (const fs::path& f : in.files) {
        auto j = read_json_file(f);
        if (!j) fail_command(j.error());
        sources.push_back(j->value("source", std::string()));
        auto ply = io::read_ply(sources.back());
        if (!ply)
            fail_command({ply.error().code, f.string() + ": its model " + ply.error().message});
        meshes.push_back(
            {.vertices = std::move(ply->cloud), .triangles = std::move(ply->triangles)});
        if (meshes.back().triangles.empty())
            fail_command({ErrorCode::kFormat, sources.back() + ": a mesh is needed"});
    }
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const std::string& source = sources[i];
        p.blocks.push_back(ra::assembly_block(in.ids[i], meshes[i]));
        if (!p.blocks.back().features.matchable())
            fail_command({ErrorCode::kInvalidArgument,
                          source + ": " + ra::to_string(p.blocks.back().features.status) + ": " +
                              p.blocks.back().features.message});
    }
}

// A face named by the user must be one of the features file's faces.
void check_face_listed(const FeatureFiles& in, const ra::FaceRef& r) {
    if (r.face >= 0 && std::size_t(r.face) < in.face_counts[std::size_t(r.block)]) return;
    fail_command({ErrorCode::kInvalidArgument,
                  in.ids[std::size_t(r.block)] + ":" + std::to_string(r.face) +
                      ": no such face (the block has " +
                      std::to_string(in.face_counts[std::size_t(r.block)]) + ")"});
}

ra::FaceLink parse_link(const FeatureFiles& in, const std::string& text) {
    const std::vector<std::string>& ids = in.ids;
    const auto eq = text.find('=');
    if (eq == std::string::npos)
        fail_command({ErrorCode::kInvalidArgument, "'" + text + "': expected A:F=B:G"});
    auto a = parse_face_ref(ids, text.substr(0, eq));
    auto b = parse_face_ref(ids, text.substr(eq + 1));
    if (!a) fail_command(a.error());
    if (!b) fail_command(b.error());
    if (a->block == b->block)
        fail_command({ErrorCode::kInvalidArgument, "'" + text + "': both faces on one block"});
    check_face_listed(in, *a);
    check_face_listed(in, *b);
    return {*a, *b};
}

ra::LineLink parse_line_link(const FeatureFiles& in, const std::string& text) {
    const std::vector<std::string>& ids = in.ids;
    auto one = [&](std::string s) {
        const auto slash = s.rfind('/');
        if (slash == std::string::npos)
            fail_command({ErrorCode::kInvalidArgument,
                          "'" + text + "': a line is BLOCK:F/G (the edge of faces F, G)"});
        auto a = parse_face_ref(ids, s.substr(0, slash));
        if (!a) fail_command(a.error());
        try {
            return ra::LineRef{a->block, a->face, std::stoi(s.substr(slash + 1))};
        } catch (const std::exception&) {
            fail_command({ErrorCode::kInvalidArgument, "'" + text + "': the face is not a number"});
        }
    };
    const auto eq = text.find('=');
    if (eq == std::string::npos)
        fail_command({ErrorCode::kInvalidArgument, "'" + text + "': expected A:F/G=B:H/K"});
    return {one(text.substr(0, eq)), one(text.substr(eq + 1))};
}

// The accepted pairs of a proposals file (blocks match, after blocks accept).
std::vector<std::string> accepted_pairs(const std::string& path) {
    auto j = read_json_file(path);
    if (!j) fail_command(j.error());
    std::set<std::pair<std::string, std::string>> seen;
    std::vector<std::string> out;
    for (const json& p : j->value("proposals", json::array()))
        for (const json& c : p.value("candidates", json::array())) {
            if (!c.value("accepted", false)) continue;
            std::string a = p.value("face", ""), b = c.value("face", "");
            if (b < a) std::swap(a, b);
            if (seen.insert({a, b}).second) out.push_back(a + "=" + b);
        }
    if (out.empty())
        fail_command({ErrorCode::kInvalidArgument, path + ": no accepted pair (blocks accept)"});
    return out;
}

PointCloud coloured_model(const ra::AssemblyProblem& p, const std::vector<Pose>& T,
                          const ra::AssemblyCheck& check) {
    static constexpr Rgb8 kColours[] = {{230, 159, 0},  {86, 180, 233}, {0, 158, 115},
                                        {240, 228, 66}, {0, 114, 178},  {204, 121, 167},
                                        {140, 140, 60}};
    PointCloud out;
    for (std::size_t b = 0; b < p.blocks.size(); ++b)
        for (std::size_t i = 0; i < p.blocks[b].points.size(); ++i) {
            out.positions.push_back(
                (T[b] * p.blocks[b].points.positions[i].cast<double>()).cast<float>());
            out.colors.push_back(check.depth_m[b][i] > 0.0f ? Rgb8{255, 0, 0} : kColours[b % 7]);
        }
    return out;
}

void write_outputs(const AssembleBlocksOptions& o, const ra::AssemblyProblem& p,
                   const ra::AssemblyResult& r, const ra::AssemblyCheck& check, double seconds) {
    std::error_code ec;
    fs::create_directories(o.out, ec);
    if (ec) fail_command({ErrorCode::kIo, o.out + ": cannot create: " + ec.message()});
    io::StanfordConf conf;
    for (std::size_t b = 0; b < p.blocks.size(); ++b) {
        auto j = read_json_file(fs::path(o.dir) / (p.blocks[b].id + ".features.json"));
        const std::string source =
            j ? j->value("source", p.blocks[b].id + ".ply") : p.blocks[b].id + ".ply";
        conf.entries.push_back({fs::absolute(source).string(), r.T_world_block[b]});
    }
    if (auto ok = io::write_conf(fs::path(o.out) / "assembly.conf", conf); !ok)
        fail_command(ok.error());
    if (auto ok = write_json_file(fs::path(o.out) / "assembly.json",
                                  assembly_report_json(p, r, check, seconds));
        !ok)
        fail_command(ok.error());
    if (auto ok = io::write_ply((fs::path(o.out) / "assembly.ply").string(),
                                coloured_model(p, r.T_world_block, check));
        !ok)
        fail_command(ok.error());
}

// The expert's links and fixed blocks, parsed against the block ids (before any model is
// read: a typo fails at once).
ra::AssemblyProblem parse_problem(const AssembleBlocksOptions& o, const FeatureFiles& in) {
    const std::vector<std::string>& ids = in.ids;
    if (!o.proposals.empty() && !o.accepted)
        fail_command({ErrorCode::kInvalidArgument,
                      "--proposals needs --accepted (only accepted pairs are assembled)"});
    ra::AssemblyProblem p;
    const std::vector<std::string> pairs =
        o.proposals.empty() ? o.pairs : accepted_pairs(o.proposals);
    for (const std::string& t : pairs) p.contacts.push_back(parse_link(in, t));
    for (const std::string& t : o.coplanar) p.coplanar.push_back(parse_link(in, t));
    for (const std::string& t : o.colinear) p.colinear.push_back(parse_line_link(in, t));
    for (const std::string& f : o.fixed) {
        const auto it = std::find(ids.begin(), ids.end(), f);
        if (it == ids.end())
            fail_command(
                {ErrorCode::kInvalidArgument, "--fixed " + f + ": no such block in " + o.dir});
        p.fixed.push_back(int(it - ids.begin()));
    }
    return p;
}

void run_assemble_blocks(const AssembleBlocksOptions& o) {
    const FeatureFiles files = feature_files(o.dir);
    ra::AssemblyProblem p = parse_problem(o, files);
    load_blocks(files, p);
    const ra::AssemblyConfig config{.max_iterations = o.max_iterations,
                                    .joint_normal = o.joint_normal == "plane"
                                                        ? ra::JointNormal::kFacePlane
                                                        : ra::JointNormal::kVertex};
    auto start = ra::initial_placement(p, config);
    if (!start) fail_command(start.error());
    const Stopwatch watch;
    auto r = ra::assemble_blocks(p, *start, config);
    if (!r) fail_command(r.error());
    const ra::AssemblyCheck check = ra::check_assembly(p, r->T_world_block);
    write_outputs(o, p, *r, check, watch.seconds());
    print_assembly_report(p, *r, check);
    if (r->status != ra::AssemblyStatus::kOk)
        throw CommandFailed(std::string(ra::to_string(r->status)) + ": " + r->message +
                            (r->offending.empty() ? "" : ": ") + [&] {
                                std::string s;
                                for (const auto& x : r->offending) s += (s.empty() ? "" : ", ") + x;
                                return s;
                            }());
}

}  // namespace

void add_blocks_assemble_command(CLI::App& blocks) {
    auto o = std::make_shared<AssembleBlocksOptions>();
    auto* cmd = blocks.add_subcommand(
        "assemble",
        "Penetration-free alignment of neighbouring blocks (faces touching, co-planar, co-linear)");
    cmd->add_option("dir", o->dir, "Folder of blocks features (ID.features.json)")->required();
    cmd->add_option("--pair", o->pairs,
                    "Matching faces that touch, A:F=B:G (face ids of blocks features)");
    cmd->add_option("--coplanar", o->coplanar, "Faces that should be co-planar, A:F=B:G");
    cmd->add_option("--colinear", o->colinear,
                    "Edges that should be co-linear, A:F/G=B:H/K (edge of faces F, G)");
    cmd->add_option("--fixed", o->fixed, "Blocks that stay in place (default: the first)");
    cmd->add_option("--proposals", o->proposals, "proposals.json of blocks match")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--accepted", o->accepted, "Assemble the pairs accepted in --proposals");
    cmd->add_option("--max-iterations", o->max_iterations, "Iterations at most")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--joint-normal", o->joint_normal,
                    "Contact rows along the partner's vertex normals (vertex, default) or its "
                    "face plane (plane)")
        ->check(CLI::IsMember({"vertex", "plane"}));
    cmd->add_option("--out", o->out, "Output folder (assembly.conf, assembly.json, assembly.ply)")
        ->required();
    cmd->callback([o] {
        if (o->pairs.empty() && o->proposals.empty())
            fail_command({ErrorCode::kInvalidArgument,
                          "give --pair A:F=B:G or --proposals FILE --accepted"});
        run_assemble_blocks(*o);
    });
}

}  // namespace anascan::cli
