// load_folder_blocks: the models a blocks folder names, read and given their features (kept
// apart from the folder's parsing, which needs no geometry).
#include "anascan/acquisition/blocks/block_folder.hpp"
#include "anascan/processing/io/ply.hpp"

namespace anascan::acquisition {

namespace ra = reassembly;

Expected<std::vector<ra::AssemblyBlock>> load_folder_blocks(const BlockFolder& folder,
                                                            const LoadProgress& progress) {
    std::vector<Mesh> meshes;
    for (std::size_t i = 0; i < folder.models.size(); ++i) {
        auto ply = io::read_ply(folder.models[i].string());
        if (!ply)
            return fail(ply.error().code,
                        folder.feature_files[i].string() + ": its model " + ply.error().message);
        if (ply->triangles.empty())
            return fail(ErrorCode::kFormat, folder.models[i].string() + ": a mesh is needed");
        meshes.push_back(
            {.vertices = std::move(ply->cloud), .triangles = std::move(ply->triangles)});
    }
    std::vector<ra::AssemblyBlock> blocks;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        if (progress) progress(i, meshes.size());
        blocks.push_back(ra::assembly_block(folder.ids[i], meshes[i]));
        const ra::BlockFeatures& f = blocks.back().features;
        if (!f.matchable())
            return fail(
                ErrorCode::kInvalidArgument,
                folder.models[i].string() + ": " + ra::to_string(f.status) + ": " + f.message);
        meshes[i] = Mesh{};  // the block holds its own copy
    }
    if (progress) progress(meshes.size(), meshes.size());
    return blocks;
}

}  // namespace anascan::acquisition
