#pragma once
/// \file
/// anascan-field --assembly DIR: the archaeologist's assembly view. The blocks of a folder
/// of block features in 3D, the proposals to choose face pairs from, the alignment run in
/// the background, its report and colours, and "Accept" writing the assembly folder.
/// Headless (tests): choose pairs, align, accept, then count frames and take the screenshot.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace anascan::field {

struct FieldAppConfig;

struct AssemblyOptions {
    std::optional<std::filesystem::path> dir;        ///< --assembly: folder of blocks features.
    std::optional<std::filesystem::path> proposals;  ///< Default: DIR/proposals.json.
    std::optional<std::filesystem::path> out;        ///< Default: DIR/assembly.
    std::vector<std::string> fixed;
    // The headless operator.
    std::vector<std::string> click_blocks;     ///< Click these blocks in the view (centres).
    std::vector<std::string> choose_pairs;     ///< Tick these pairs once loaded.
    std::vector<std::string> choose_coplanar;  ///< Then these co-planar links.
    bool choose_accepted = false;              ///< Tick the proposals' accepted pairs.
    bool align = false;                        ///< Then press "Align".
    bool accept = false;                       ///< Then "Accept and save" (an ok alignment).
};

/// Runs the assembly view; returns the process exit code.
int run_assembly_app(const FieldAppConfig& config);

}  // namespace anascan::field
