#pragma once
// The fixture of the `anascan blocks` CLI tests: blocks of the simulated monument exported
// and their features found, as a user does before matching or assembling; faces named
// through the truth file, as an expert points at them.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../cli_runner.hpp"

namespace anascan {

inline nlohmann::json read_json(const std::filesystem::path& p) {
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

class BlocksCli : public testing_util::Cli {
protected:
    // The face of block `id` whose normal is the block axis `axis` (a column of
    // T_ground_block's rotation) times `sign`.
    int face_along(const std::string& id, int axis, double sign) {
        const nlohmann::json f = read_json(dir_ / "f" / (id + ".features.json"));
        const nlohmann::json truth = read_json(dir_ / "m" / "truth.json");
        for (const nlohmann::json& b : truth.at("blocks")) {
            if (b.at("id") != id) continue;
            for (const nlohmann::json& face : f.at("faces")) {
                double dot = 0.0;
                for (int r = 0; r < 3; ++r)
                    dot += sign * b.at("T_ground_block").at(r).at(axis).get<double>() *
                           face.at("normal").at(r).get<double>();
                if (dot > 0.99) return face.at("id").get<int>();
            }
        }
        ADD_FAILURE() << id << ": no face along axis " << axis << " sign " << sign;
        return -1;
    }
    // Exports the blocks (comma-separated ids) of octagon-wall to m/ and finds their
    // features in f/.
    void export_blocks(const std::string& ids) {
        ASSERT_EQ(testing_util::run_cli("sim export-monument octagon-wall --step-mm 5 --blocks " +
                                        ids + " --out " + (dir_ / "m").string())
                      .exit_code,
                  0);
        std::string models;
        std::stringstream list(ids);
        for (std::string id; std::getline(list, id, ',');)
            models += (dir_ / "m/blocks" / (id + ".ply")).string() + " ";
        const auto r =
            testing_util::run_cli("blocks features " + models + "--out " + (dir_ / "f").string());
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }
};

}  // namespace anascan
