#pragma once
/// \file
/// The proposals file of `anascan blocks match` (proposals.json) as the assembly reads it:
/// for every face its ranked candidates with score, checks passed and the expert's accept.

#include <filesystem>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::acquisition {

struct ProposalCandidate {
    std::string face;  ///< "BLOCK:FACE".
    double score = 0.0;
    std::vector<std::string> passed;  ///< The checks it passed, by name.
    std::size_t checks = 0;           ///< Checks in all.
    bool accepted = false;            ///< By the expert (blocks accept).
    /// The neighbouring faces the match paired around the two faces, "A:F=B:G" each: the
    /// faces that should be co-planar when the pair touches (façade with façade, ...).
    std::vector<std::string> neighbour_pairs;
};

struct FaceProposals {
    std::string face;                           ///< "BLOCK:FACE".
    std::vector<ProposalCandidate> candidates;  ///< Best first.
};

struct BlockProposals {
    std::filesystem::path features_dir;
    std::vector<FaceProposals> faces;
};

/// kIo / kFormat naming the file.
Expected<BlockProposals> read_block_proposals(const std::filesystem::path& path);

/// "A:F=B:G" for a pair, its faces in name order (so each pair has one name).
std::string pair_name(std::string a, std::string b);

/// The accepted pairs, each once, in the file's order.
std::vector<std::string> accepted_pairs(const BlockProposals& proposals);

}  // namespace anascan::acquisition
