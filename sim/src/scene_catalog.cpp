#include <algorithm>
#include <charconv>
#include <cstdio>
#include <string>

#include "anascan/sim/scene.hpp"
#include "hash_random.hpp"

namespace anascan::sim {
namespace {

SceneConfig octagon_block() {
    return SceneConfig{.name = "octagon-block"};  // 1.2 x 0.6 x 0.5 m, every feature.
}

SceneConfig small_block() {
    return SceneConfig{
        .name = "small-block",
        .block =
            StoneBlockConfig{
                .size_m = {0.45, 0.4, 0.35},
                .grid_step_m = 0.002,
                .clamp_holes = {ClampHole{.edge_face = BlockFace::kPosX, .length_m = 0.1}},
                .dowel_holes = {DowelHole{.face = BlockFace::kNegZ, .radius_m = 0.015}},
                .ornament = OrnamentBand{.face = BlockFace::kNegY,
                                         .top_offset_m = 0.035,
                                         .height_m = 0.06,
                                         .period_m = 0.045,
                                         .depth_m = 0.01},
                .chip_count = 4,
                .chip_max_depth_m = 0.015,
                .chip_max_half_length_m = 0.05,
                .seed = 2},
        .placement = BlockPlacement{.yaw_deg = 15.0}};
}

SceneConfig large_block() {
    SceneConfig config{
        .name = "large-block",
        .block = StoneBlockConfig{
            .size_m = {1.5, 0.8, 0.7}, .grid_step_m = 0.003, .chip_count = 12, .seed = 3}};
    config.block.clamp_holes.push_back(ClampHole{.edge_face = BlockFace::kPosY, .offset_m = 0.3});
    return config;
}

SceneConfig turned(SceneConfig config, BlockFace resting_face, double yaw_deg) {
    config.name += resting_face == BlockFace::kPosZ ? "-turned" : "-on-side";
    config.placement.resting_face = resting_face;
    config.placement.yaw_deg = yaw_deg;
    return config;
}

constexpr std::string_view kRandomPrefix = "random-block:";

/// `random-block:SEED`: a block of 0.4-1.5 m edges (its height at most its width), its
/// features (holes, ornament, chips) and its yaw drawn from the seed; the mesh step follows
/// the size (2 mm up to 0.6 m, then 3 mm, as the named scenes).
SceneConfig random_block(std::uint64_t seed) {
    const auto unit = [seed](std::uint64_t k) {
        return detail::unit_from_hash(detail::hash3(seed, 0x5CE4E, k));
    };
    const double a = 0.4 + 1.1 * unit(0), b = 0.4 + 1.1 * unit(1), c = 0.4 + 1.1 * unit(2);
    const double length = std::max(a, b), width = std::min(a, b), height = std::min(c, width);
    SceneConfig config{.name = std::string(kRandomPrefix) + std::to_string(seed)};
    StoneBlockConfig& block = config.block;
    block.size_m = {length, width, height};
    block.grid_step_m = length > 0.6 ? 0.003 : 0.002;
    block.seed = static_cast<std::uint32_t>(seed);
    block.chip_count = 2 + static_cast<int>(unit(3) * 10.0);
    block.chip_max_depth_m = 0.01 + 0.02 * unit(4);
    block.chip_max_half_length_m = std::min(0.1, 0.15 * width);
    block.clamp_holes = {ClampHole{.edge_face = unit(5) < 0.5 ? BlockFace::kPosX : BlockFace::kPosY,
                                   .length_m = std::min(0.12, 0.3 * width)}};
    block.dowel_holes = {DowelHole{.face = BlockFace::kNegZ, .radius_m = 0.015}};
    block.ornament.face = unit(6) < 0.5 ? BlockFace::kNegY : BlockFace::kPosX;
    block.ornament.height_m = std::min(block.ornament.height_m, 0.3 * height);
    config.placement.yaw_deg = 360.0 * unit(7);
    return config;
}

std::vector<SceneConfig> all_scenes() {
    return {octagon_block(), turned(octagon_block(), BlockFace::kPosZ, 20.0),
            small_block(),   turned(small_block(), BlockFace::kPosZ, -30.0),
            large_block(),   turned(large_block(), BlockFace::kPosY, 10.0)};
}

std::string describe(const SceneConfig& c) {
    char text[160];
    static const char* kFaces[] = {"+x", "-x", "+y", "-y", "+z (turned over)", "-z (upright)"};
    std::snprintf(text, sizeof(text), "%.2f x %.2f x %.2f m block, %.1f mm mesh, resting on %s",
                  c.block.size_m.x(), c.block.size_m.y(), c.block.size_m.z(),
                  1000.0 * c.block.grid_step_m, kFaces[static_cast<int>(c.placement.resting_face)]);
    return text;
}

}  // namespace

std::vector<SceneInfo> scene_catalog() {
    std::vector<SceneInfo> infos;
    for (const SceneConfig& c : all_scenes()) infos.push_back({c.name, describe(c)});
    infos.push_back(
        {"random-block:SEED", "a block of 0.4-1.5 m edges, its features and yaw drawn from SEED"});
    return infos;
}

Expected<SceneConfig> named_scene(std::string_view name) {
    if (name.starts_with(kRandomPrefix)) {
        const std::string_view digits = name.substr(kRandomPrefix.size());
        std::uint64_t seed = 0;
        const auto [end, error] =
            std::from_chars(digits.data(), digits.data() + digits.size(), seed);
        if (error == std::errc() && end == digits.data() + digits.size() && !digits.empty())
            return random_block(seed);
        return fail(ErrorCode::kInvalidArgument, "scene '" + std::string(name) +
                                                     "': a random block is random-block:SEED, "
                                                     "SEED a non-negative integer");
    }
    std::string known;
    for (const SceneConfig& c : all_scenes()) {
        if (c.name == name) return c;
        known += (known.empty() ? "" : ", ") + c.name;
    }
    known += ", random-block:SEED";
    return fail(ErrorCode::kInvalidArgument,
                "unknown scene '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace anascan::sim
