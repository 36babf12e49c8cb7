#include "anascan/acquisition/blocks/block_alignment.hpp"

#include <algorithm>
#include <cmath>

#include "anascan/acquisition/blocks/block_features_file.hpp"
#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/io/ply.hpp"
#include "anascan/processing/io/stanford_conf.hpp"
#include "anascan/processing/reassembly/assembly_probe.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;
namespace ra = reassembly;
using nlohmann::json;

json pose_rows(const Pose& T) {
    json rows = json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
    return rows;
}

json check_json(const ra::AssemblyCheck& c) {
    json contacts = json::array(), coplanar = json::array(), colinear = json::array();
    for (const auto& x : c.contacts)
        contacts.push_back({{"pair", x.pair},
                            {"points", x.points},
                            {"gap_median_mm", 1e3 * x.gap_median_m},
                            {"gap_p95_mm", 1e3 * x.gap_p95_m},
                            {"gap_max_mm", 1e3 * x.gap_max_m},
                            {"gap_min_mm", 1e3 * x.gap_min_m}});
    for (const auto& x : c.coplanar)
        coplanar.push_back(
            {{"pair", x.pair}, {"angle_deg", x.angle_deg}, {"offset_mm", 1e3 * x.offset_m}});
    for (const auto& x : c.colinear)
        colinear.push_back(
            {{"pair", x.pair}, {"angle_deg", x.angle_deg}, {"distance_mm", 1e3 * x.distance_m}});
    return {{"penetration_max_mm", 1e3 * c.penetration_max_m},
            {"penetration_mean_mm", 1e3 * c.penetration_mean_m},
            {"penetrating_points", c.penetrating_points},
            {"measured_points", c.measured_points},
            {"contacts", contacts},
            {"coplanar", coplanar},
            {"colinear", colinear}};
}

bool is_fixed(const ra::AssemblyProblem& p, std::size_t b) {
    return std::count(p.fixed.begin(), p.fixed.end(), int(b)) > 0 || (p.fixed.empty() && b == 0);
}

json report_json(const ra::AssemblyProblem& p, const BlockAlignment& a) {
    json blocks = json::array(), history = json::array();
    for (std::size_t b = 0; b < p.blocks.size(); ++b)
        blocks.push_back({{"id", p.blocks[b].id},
                          {"fixed", is_fixed(p, b)},
                          {"T_assembly_model", pose_rows(a.result.T_world_block[b])}});
    for (const auto& h : a.result.history)
        history.push_back({{"registration_rms_mm", 1e3 * h.registration_rms_m},
                           {"coplanar_rms_mm", 1e3 * h.coplanar_rms_m},
                           {"colinear_rms_mm", 1e3 * h.colinear_rms_m},
                           {"constraint_samples", h.constraint_samples},
                           {"active_constraints", h.active_constraints}});
    return {{"status", ra::to_string(a.result.status)},
            {"message", a.result.message},
            {"offending", a.result.offending},
            {"iterations", a.result.iterations},
            {"seconds", a.seconds},
            {"blocks", blocks},
            {"history", history},
            {"check", check_json(a.check)}};
}

Rgb8 mix(Rgb8 a, Rgb8 b, double t) {
    auto c = [t](std::uint8_t x, std::uint8_t y) {
        return std::uint8_t(std::lround((1.0 - t) * x + t * y));
    };
    return {c(a.r, b.r), c(a.g, b.g), c(a.b, b.b)};
}

}  // namespace

LinkedBlocks linked_blocks(const ra::AssemblyProblem& whole) {
    std::vector<int> index(whole.blocks.size(), -1);
    LinkedBlocks out;
    auto take = [&](int b) {
        if (b < 0 || std::size_t(b) >= whole.blocks.size()) return b;  // validation names it
        if (index[std::size_t(b)] < 0) {
            index[std::size_t(b)] = int(out.blocks.size());
            out.blocks.push_back(std::size_t(b));
            out.problem.blocks.push_back(whole.blocks[std::size_t(b)]);
        }
        return index[std::size_t(b)];
    };
    for (int b : whole.fixed) out.problem.fixed.push_back(take(b));
    // Without fixed blocks the first block stays still, as in the whole problem, when linked.
    auto names_first = [](const ra::FaceLink& l) { return l.a.block == 0 || l.b.block == 0; };
    if (whole.fixed.empty() &&
        (std::any_of(whole.contacts.begin(), whole.contacts.end(), names_first) ||
         std::any_of(whole.coplanar.begin(), whole.coplanar.end(), names_first)))
        take(0);
    auto face = [&](ra::FaceRef r) { return ra::FaceRef{take(r.block), r.face}; };
    auto line = [&](ra::LineRef r) { return ra::LineRef{take(r.block), r.face_a, r.face_b}; };
    for (const ra::FaceLink& l : whole.contacts)
        out.problem.contacts.push_back({face(l.a), face(l.b)});
    for (const ra::FaceLink& l : whole.coplanar)
        out.problem.coplanar.push_back({face(l.a), face(l.b)});
    for (const ra::LineLink& l : whole.colinear)
        out.problem.colinear.push_back({line(l.a), line(l.b)});
    return out;
}

Expected<BlockAlignment> align_blocks(const ra::AssemblyProblem& problem,
                                      const ra::AssemblyConfig& config) {
    const Stopwatch watch;
    auto start = ra::initial_placement(problem, config);
    if (!start) return fail(start.error());
    auto r = ra::assemble_blocks(problem, *start, config);
    if (!r) return fail(r.error());
    if (r->status == ra::AssemblyStatus::kOk) {
        auto fixed = ra::probe_determinacy(problem, *r, config);
        if (!fixed) return fail(fixed.error());
        ra::mark_underdetermined(problem, *fixed, *r);
    } else if (r->status == ra::AssemblyStatus::kNotConverged) {
        auto why = ra::diagnose_not_converged(problem, *r, config);
        if (!why) return fail(why.error());
        ra::name_non_convergence(problem, *why, *r);
    }
    BlockAlignment out{.result = std::move(*r)};
    out.check = ra::check_assembly(problem, out.result.T_world_block);
    out.seconds = watch.seconds();
    return out;
}

Rgb8 block_colour(std::size_t block) {
    // Okabe & Ito's colour-blind safe palette, without its red (penetration) and black.
    static constexpr Rgb8 kColours[] = {{230, 159, 0},  {86, 180, 233}, {0, 158, 115},
                                        {240, 228, 66}, {0, 114, 178},  {204, 121, 167},
                                        {140, 140, 60}};
    return kColours[block % std::size(kColours)];
}

Rgb8 assembly_point_colour(Rgb8 block, float depth_m, float gap_m) {
    if (depth_m > 0.0f) return {255, 0, 0};
    if (std::isnan(gap_m)) return block;
    constexpr Rgb8 kTouching{60, 200, 60}, kHalfway{250, 230, 40}, kApart{40, 60, 255};
    const double mm = 1e3 * std::max(0.0f, gap_m);
    if (mm <= 1.0) return kTouching;
    if (mm <= 3.0) return mix(kTouching, kHalfway, (mm - 1.0) / 2.0);
    return mix(kHalfway, kApart, std::min(1.0, (mm - 3.0) / 2.0));
}

PointCloud coloured_block(const ra::AssemblyProblem& p, const ra::AssemblyCheck& check,
                          std::size_t b, Rgb8 colour) {
    const PointCloud& points = p.blocks[b].points;
    PointCloud out;
    out.positions = points.positions;
    out.colors.reserve(points.size());
    const bool checked = b < check.depth_m.size() && b < check.gap_m.size();
    for (std::size_t i = 0; i < points.size(); ++i)
        out.colors.push_back(
            checked ? assembly_point_colour(colour, check.depth_m[b][i], check.gap_m[b][i])
                    : colour);
    return out;
}

Expected<void> write_assembly_folder(const fs::path& out, const BlockFolder& folder,
                                     const ra::AssemblyProblem& p, const BlockAlignment& a) {
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) return fail(ErrorCode::kIo, out.string() + ": cannot create: " + ec.message());
    io::StanfordConf conf;
    PointCloud model;
    for (std::size_t b = 0; b < p.blocks.size(); ++b) {
        const auto index = std::find(folder.ids.begin(), folder.ids.end(), p.blocks[b].id);
        const fs::path source = index != folder.ids.end()
                                    ? folder.models[std::size_t(index - folder.ids.begin())]
                                    : fs::path(p.blocks[b].id + ".ply");
        const Pose& T = a.result.T_world_block[b];
        conf.entries.push_back({fs::absolute(source).string(), T});
        PointCloud block = coloured_block(p, a.check, b, block_colour(b));
        for (std::size_t i = 0; i < block.size(); ++i) {
            model.positions.push_back((T * block.positions[i].cast<double>()).cast<float>());
            model.colors.push_back(block.colors[i]);
        }
    }
    if (auto ok = io::write_conf(out / "assembly.conf", conf); !ok) return ok;
    if (auto ok = write_json_file(out / "assembly.json", report_json(p, a)); !ok) return ok;
    return io::write_ply((out / "assembly.ply").string(), model);
}

}  // namespace anascan::acquisition
