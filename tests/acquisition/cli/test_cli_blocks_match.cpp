// `anascan blocks match`, `accept`, `reject` and `eval PROPOSALS.json` as a user runs them:
// three neighbours of the first course of the simulated monument exported and their
// features found; the proposals ranked against the truth; an expert's rejection and
// acceptance respected by the next match; and the bad inputs (a face the block does not
// have, a pair on one block, a folder without features, a missing truth file).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "blocks_cli.hpp"

namespace anascan {
namespace {

using nlohmann::json;
using testing_util::run_cli;
using testing_util::run_cli_stdout;

class BlocksMatchCli : public BlocksCli {
protected:
    std::string ref(const std::string& id, int axis, double sign) {
        return id + ":" + std::to_string(face_along(id, axis, sign));
    }
    json match_and_eval() {
        const auto m = run_cli("blocks match " + (dir_ / "f").string() + " --out " + proposals());
        EXPECT_EQ(m.exit_code, 0) << m.output;
        EXPECT_NE(m.output.find("checks passed"), std::string::npos) << m.output;
        const auto e = run_cli_stdout("blocks eval " + proposals() + " --truth " +
                                      (dir_ / "m/truth.json").string() + " --json");
        EXPECT_EQ(e.exit_code, 0) << e.output;
        return json::parse(e.output);
    }
    // The rank of the true neighbour of a block's face ("+x", "-x", ...), -1 when unranked.
    static int rank_of(const json& eval, const std::string& block, const std::string& face) {
        for (const json& r : eval.at("ranks"))
            if (r.at("block") == block && r.at("face") == face) return r.at("rank").get<int>();
        return -1;
    }
    // The candidates of a face in the proposals file, best first.
    std::vector<std::string> candidates_of(const std::string& face) {
        std::vector<std::string> out;
        const json all = read_json(proposals());  // Kept alive through the loop.
        for (const json& p : all.at("proposals"))
            if (p.at("face") == face)
                for (const json& c : p.at("candidates")) out.push_back(c.at("face"));
        return out;
    }
    std::string proposals() const { return (dir_ / "proposals.json").string(); }
};

TEST_F(BlocksMatchCli, ProposalsDecisionsAndBadInputs) {
    export_blocks("c0b0,c0b1,c0b2");
    // Only these three blocks of the wall are here: their two vertical joints are scored.
    const json before = match_and_eval();
    EXPECT_EQ(rank_of(before, "c0b0", "+x"), 1) << before.dump();
    EXPECT_EQ(rank_of(before, "c0b1", "-x"), 1) << before.dump();
    EXPECT_LE(rank_of(before, "c0b2", "-x"), 3) << before.dump();

    // Rejecting the true pair drops it from the next match; accepting a wrong one puts it
    // first, marked.
    const std::string joint_a = ref("c0b0", 0, 1), joint_b = ref("c0b1", 0, -1);
    ASSERT_EQ(run_cli("blocks reject " + proposals() + " " + joint_a + " " + joint_b).exit_code, 0);
    const std::string facade = ref("c0b1", 1, 1), back = ref("c0b2", 1, -1);
    ASSERT_EQ(run_cli("blocks accept " + proposals() + " " + facade + " " + back).exit_code, 0);
    const json after = match_and_eval();
    EXPECT_NE(rank_of(after, "c0b0", "+x"), 1);
    const std::vector<std::string> of_joint = candidates_of(joint_a);
    ASSERT_FALSE(of_joint.empty());
    EXPECT_EQ(std::find(of_joint.begin(), of_joint.end(), joint_b), of_joint.end());
    const std::vector<std::string> of_facade = candidates_of(facade);
    ASSERT_FALSE(of_facade.empty());
    EXPECT_EQ(of_facade.front(), back);

    // Bad inputs: each a clear message and a failing exit code; no decision recorded.
    const std::string decisions_before =
        read_json(dir_ / "f/decisions.json").at("decisions").dump();
    auto fails_with = [&](const std::string& args, const std::string& text) {
        const auto b = run_cli(args);
        EXPECT_NE(b.exit_code, 0) << args;
        EXPECT_NE(b.output.find(text), std::string::npos) << args << "\n" << b.output;
    };
    fails_with("blocks accept " + proposals() + " c0b1:77 " + back, "block c0b1 has no face 77");
    fails_with("blocks reject " + proposals() + " " + facade + " " + ref("c0b1", 1, -1),
               "faces of one block");
    fails_with("blocks accept " + proposals() + " c9b9:0 " + back, "no block c9b9");
    EXPECT_EQ(read_json(dir_ / "f/decisions.json").at("decisions").dump(), decisions_before);
    std::filesystem::create_directories(dir_ / "empty");
    fails_with("blocks match " + (dir_ / "empty").string() + " --out " + (dir_ / "x.json").string(),
               "no *.features.json");
    fails_with("blocks eval " + proposals() + " --truth " + (dir_ / "none.json").string(),
               "none.json");
    // Files of the right syntax holding values of the wrong type: named, not a crash.
    std::ofstream(dir_ / "f/decisions.json") << R"({"decisions": 5})";
    fails_with("blocks match " + (dir_ / "f").string() + " --out " + (dir_ / "y.json").string(),
               "not a decisions file");
    std::ofstream(dir_ / "typed.json") << R"({"features_dir": ".", "blocks": 5})";
    fails_with("blocks accept " + (dir_ / "typed.json").string() + " " + facade + " " + back,
               "not a file of blocks match");
}

}  // namespace
}  // namespace anascan
