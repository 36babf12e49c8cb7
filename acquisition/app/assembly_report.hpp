#pragma once
// The table printed by `blocks assemble` (assembly.json: acquisition/blocks).
#include "anascan/processing/reassembly/assembly_check.hpp"
#include "anascan/processing/reassembly/block_assembly.hpp"

namespace anascan::cli {

void print_assembly_report(const reassembly::AssemblyProblem& problem,
                           const reassembly::AssemblyResult& result,
                           const reassembly::AssemblyCheck& check);

}  // namespace anascan::cli
