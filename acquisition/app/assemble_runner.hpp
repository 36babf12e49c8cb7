#pragma once
// Shared by `assemble` and `demo`.
#include <spdlog/spdlog.h>

#include <string>

#include "anascan/acquisition/assembly/assembly.hpp"

namespace anascan::cli {

struct AssembleOptions {
    std::string conf;
    std::string model_out;
    std::string report_out;
    double voxel_mm = 0.0;
    double overlap_radius_mm = 5.0;
    double min_overlap_percent = 10.0;
};

/// Runs the assembly, prints the pair table and writes the requested outputs.
acquisition::AssemblyReport run_assemble(const AssembleOptions& options);

}  // namespace anascan::cli
