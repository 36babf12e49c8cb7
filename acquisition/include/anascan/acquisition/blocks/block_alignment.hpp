#pragma once
/// \file
/// One run of the penetration-free alignment as the commands and the field app's assembly
/// view run it: the Horn placement from the face pairs, the constrained registration of all
/// blocks, the check on the dense models; the placed models coloured for the eye; and the
/// assembly folder (assembly.conf, assembly.json, assembly.ply).

#include <filesystem>

#include "anascan/acquisition/blocks/block_folder.hpp"
#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/reassembly/assembly_check.hpp"
#include "anascan/processing/reassembly/block_assembly.hpp"

namespace anascan::acquisition {

struct BlockAlignment {
    reassembly::AssemblyResult result;
    reassembly::AssemblyCheck check;
    double seconds = 0.0;  ///< Placement, registration and check, wall time.
};

/// The blocks a problem's links name (and its fixed blocks) as a problem of their own, so
/// that a few pairs chosen among many blocks align those blocks and leave the rest alone.
/// Without fixed blocks its first block stays still: the whole problem's first block when a
/// link names it, else the first block the links name.
struct LinkedBlocks {
    reassembly::AssemblyProblem problem;  ///< Block indices renumbered, blocks copied.
    std::vector<std::size_t> blocks;      ///< Its blocks' indices in the whole problem.
};
LinkedBlocks linked_blocks(const reassembly::AssemblyProblem& whole);

/// Places, registers, probes whether the pairs fix every block (assembly_probe.hpp) and
/// checks; an error when the problem is refused (unknown face, a sliver, a block no pair
/// links to a fixed one). A status other than kOk (infeasible, contradictory, not
/// converged, underdetermined) is a result, with its offending pairs.
Expected<BlockAlignment> align_blocks(const reassembly::AssemblyProblem& problem,
                                      const reassembly::AssemblyConfig& config);

/// Colours of the assembled model: a colour per block; points of a matching face by their
/// gap to the partner (green within 1 mm, through yellow to blue at 5 mm and more);
/// penetrating points red.
Rgb8 block_colour(std::size_t block);
Rgb8 assembly_point_colour(Rgb8 block, float depth_m, float gap_m);
/// Block `b`'s model points in its own frame with the colours above, `colour` its own.
PointCloud coloured_block(const reassembly::AssemblyProblem& problem,
                          const reassembly::AssemblyCheck& check, std::size_t b, Rgb8 colour);

/// Writes OUT/assembly.conf (one bmesh line per block: its model and pose), assembly.json
/// (status, offending pairs, poses, per-iteration residuals, the dense check) and
/// assembly.ply (the placed models coloured), each crash-safely; OUT is created.
Expected<void> write_assembly_folder(const std::filesystem::path& out, const BlockFolder& folder,
                                     const reassembly::AssemblyProblem& problem,
                                     const BlockAlignment& alignment);

}  // namespace anascan::acquisition
