#pragma once
// The block assembly's report: assembly.json and the table printed by `blocks assemble`.
#include <nlohmann/json.hpp>

#include "anascan/processing/reassembly/assembly_check.hpp"
#include "anascan/processing/reassembly/block_assembly.hpp"

namespace anascan::cli {

nlohmann::json assembly_report_json(const reassembly::AssemblyProblem& problem,
                                    const reassembly::AssemblyResult& result,
                                    const reassembly::AssemblyCheck& check, double seconds);
void print_assembly_report(const reassembly::AssemblyProblem& problem,
                           const reassembly::AssemblyResult& result,
                           const reassembly::AssemblyCheck& check);

}  // namespace anascan::cli
