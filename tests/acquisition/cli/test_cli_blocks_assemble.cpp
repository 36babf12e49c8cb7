// `anascan blocks assemble` and `blocks eval ASSEMBLY/` as a user runs them: two
// neighbours of the simulated monument exported, their features found, the joint faces
// (named through the truth file, as an expert would point at them) assembled, and the
// assembly scored against the truth; and the bad inputs (a missing block file, a face
// pair on one block, an unknown block or face, bad syntax, an unknown block to export).
// Only the two blocks are exported: the test takes seconds.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "blocks_cli.hpp"

namespace anascan {
namespace {

using nlohmann::json;
using testing_util::run_cli;
using testing_util::run_cli_stdout;

class BlocksAssembleCli : public BlocksCli {
protected:
    std::string pair(int axis_a, double sign_a, int axis_b, double sign_b) {
        return "c0b0:" + std::to_string(face_along("c0b0", axis_a, sign_a)) +
               "=c0b1:" + std::to_string(face_along("c0b1", axis_b, sign_b));
    }
};

TEST_F(BlocksAssembleCli, TwoNeighboursAgainstTheTruthAndBadInputs) {
    export_blocks("c0b0,c0b1");
    const std::string f = (dir_ / "f").string(), out = (dir_ / "a").string();
    const std::string joint = pair(0, 1, 0, -1), facade = pair(1, 1, 1, 1), top = pair(2, 1, 2, 1);
    const auto r = run_cli("blocks assemble " + f + " --pair " + joint + " --coplanar " + facade +
                           " --coplanar " + top + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("penetration on the dense models"), std::string::npos) << r.output;
    for (const char* file : {"assembly.conf", "assembly.json", "assembly.ply"})
        EXPECT_TRUE(std::filesystem::exists(dir_ / "a" / file)) << file;
    const auto e = run_cli_stdout("blocks eval " + out + " --truth " +
                                  (dir_ / "m/truth.json").string() + " --json");
    ASSERT_EQ(e.exit_code, 0) << e.output;
    const json score = json::parse(e.output);
    EXPECT_LT(score.at("worst_rotation_error_deg").get<double>(), 0.1);
    EXPECT_LT(score.at("worst_translation_error_mm").get<double>(), 0.5);
    EXPECT_LE(score.at("penetration_max_mm").get<double>(), 0.1);

    // Bad inputs: each a clear message and a failing exit code.
    auto fails_with = [&](const std::string& args, const std::string& text) {
        const auto b = run_cli("blocks assemble " + args + " --out " + (dir_ / "bad").string());
        EXPECT_NE(b.exit_code, 0) << args;
        EXPECT_NE(b.output.find(text), std::string::npos) << args << "\n" << b.output;
    };
    // The joint and the façades alone leave c0b1 free up and down the joint: it ends where
    // the start put it, which is not ok however well it fits.
    fails_with(f + " --pair " + joint + " --coplanar " + facade, "underdetermined");
    fails_with(f + " --pair " + joint + " --coplanar " + facade, "c0b1 slides along");
    fails_with(f + " --pair c0b0:1=c0b0:2", "both faces on one block");
    fails_with(f + " --pair c0b0:1=c9b9:2", "no block c9b9");
    fails_with(f + " --pair c0b0:1=c0b1:77", "c0b1:77: no such face");
    fails_with(f + " --pair c0b0:1", "expected A:F=B:G");
    fails_with((dir_ / "nowhere").string() + " --pair c0b0:1=c0b1:2",
               "not a folder of block features");
    json broken = read_json(dir_ / "f/c0b1.features.json");
    broken["source"] = (dir_ / "m/blocks/missing.ply").string();
    std::filesystem::create_directories(dir_ / "g");
    std::filesystem::copy_file(dir_ / "f/c0b0.features.json", dir_ / "g/c0b0.features.json");
    std::ofstream(dir_ / "g/c0b1.features.json") << broken.dump();
    fails_with((dir_ / "g").string() + " --pair " + joint, "missing.ply");
    const auto unknown =
        run_cli("sim export-monument octagon-wall --blocks c9b9 --out " + (dir_ / "m2").string());
    EXPECT_NE(unknown.exit_code, 0);
    EXPECT_NE(unknown.output.find("--blocks c9b9: no such block"), std::string::npos)
        << unknown.output;
}

}  // namespace
}  // namespace anascan
