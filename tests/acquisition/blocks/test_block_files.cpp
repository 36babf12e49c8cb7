// The block folder and proposals files as the assembly reads them: links parsed against the
// folder (typos named before any model is read), the accepted pairs of a proposals file
// (each once, one name for both orders), broken files named in the error, and the blocks
// a few pairs name taken out of a folder of many.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "anascan/acquisition/blocks/block_alignment.hpp"
#include "anascan/acquisition/blocks/block_folder.hpp"
#include "anascan/acquisition/blocks/block_proposals.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;

class BlockFiles : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("anascan_block_files_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    void write(const std::string& name, const std::string& text) {
        std::ofstream(dir_ / name) << text;
    }
    // A features file with `faces` faces (only what the folder reads).
    void features(const std::string& id, int faces) {
        std::string list;
        for (int f = 0; f < faces; ++f)
            list += (f ? ",{\"id\":" : "{\"id\":") + std::to_string(f) + "}";
        write(id + ".features.json",
              "{\"id\":\"" + id + "\",\"source\":\"" + id + ".ply\",\"faces\":[" + list + "]}");
    }
    fs::path dir_;
};

TEST_F(BlockFiles, LinksAreCheckedAgainstTheFolder) {
    features("b", 6);
    features("a", 4);
    auto folder = open_block_folder(dir_);
    ASSERT_TRUE(folder) << folder.error().message;
    EXPECT_EQ(folder->ids, (std::vector<std::string>{"a", "b"}));  // sorted by file name
    EXPECT_EQ(folder->face_counts, (std::vector<std::size_t>{4, 6}));
    auto p = parse_assembly_links(
        *folder, {.contacts = {"a:1=b:5"}, .colinear = {"a:0/1=b:2/3"}, .fixed = {"b"}});
    ASSERT_TRUE(p) << p.error().message;
    EXPECT_EQ(p->contacts.at(0).a.block, 0);
    EXPECT_EQ(p->contacts.at(0).b.face, 5);
    EXPECT_EQ(p->colinear.at(0).b.face_b, 3);
    EXPECT_EQ(p->fixed, (std::vector<int>{1}));

    auto error = [&](const AssemblyLinks& links) {
        auto q = parse_assembly_links(*folder, links);
        return q ? std::string("accepted") : q.error().message;
    };
    EXPECT_NE(error({.contacts = {"a:4=b:1"}}).find("a:4: no such face (the block has 4)"),
              std::string::npos);
    EXPECT_NE(error({.contacts = {"a:1=a:2"}}).find("both faces on one block"), std::string::npos);
    EXPECT_NE(error({.contacts = {"a:1=c:2"}}).find("no block c"), std::string::npos);
    EXPECT_NE(error({.contacts = {"a:x=b:2"}}).find("the face is not a number"), std::string::npos);
    EXPECT_NE(error({.colinear = {"a:1=b:2"}}).find("a line is BLOCK:F/G"), std::string::npos);
    EXPECT_NE(error({.fixed = {"z"}}).find("fixed block z: no such block"), std::string::npos);
}

TEST_F(BlockFiles, BrokenFoldersAreNamed) {
    EXPECT_NE(open_block_folder(dir_ / "none").error().message.find("not a folder of block"),
              std::string::npos);
    EXPECT_NE(open_block_folder(dir_).error().message.find("no ID.features.json"),
              std::string::npos);
    write("a.features.json", "{\"id\": \"a\", \"faces\": [");
    const std::string torn = open_block_folder(dir_).error().message;
    EXPECT_NE(torn.find("a.features.json: not JSON"), std::string::npos) << torn;
    write("a.features.json", "{\"id\": \"a\"}");
    const std::string partial = open_block_folder(dir_).error().message;
    EXPECT_NE(partial.find("a.features.json: not a features file"), std::string::npos) << partial;
}

TEST_F(BlockFiles, AcceptedPairsOnceEachWhateverTheOrder) {
    write("p.json", R"({"features_dir": "/f", "proposals": [
      {"face": "b:1", "candidates": [{"face": "a:2", "score": 0.9, "accepted": true,
                                      "checks": {"size": 1, "holes": 0}, "passed": ["size"],
                                      "neighbour_pairs": [[0, 3], [4, 1]]},
                                     {"face": "a:3", "score": 0.2}]},
      {"face": "a:2", "candidates": [{"face": "b:1", "score": 0.9, "accepted": true}]},
      {"face": "c:0", "candidates": [{"face": "a:5", "score": 0.5, "accepted": true}]}]})");
    auto p = read_block_proposals(dir_ / "p.json");
    ASSERT_TRUE(p) << p.error().message;
    ASSERT_EQ(p->faces.size(), 3u);
    EXPECT_EQ(p->faces[0].candidates[0].passed, (std::vector<std::string>{"size"}));
    EXPECT_EQ(p->faces[0].candidates[0].checks, 2u);
    EXPECT_FALSE(p->faces[0].candidates[1].accepted);
    EXPECT_EQ(p->faces[0].candidates[0].neighbour_pairs,
              (std::vector<std::string>{"a:3=b:0", "a:1=b:4"}));
    EXPECT_EQ(accepted_pairs(*p), (std::vector<std::string>{"a:2=b:1", "a:5=c:0"}));
    EXPECT_EQ(pair_name("b:1", "a:2"), pair_name("a:2", "b:1"));

    write("q.json", R"({"features_dir": "/f", "proposals": [{"face": "b:1"}]})");
    const std::string bad = read_block_proposals(dir_ / "q.json").error().message;
    EXPECT_NE(bad.find("q.json: not a proposals file"), std::string::npos) << bad;
}

TEST(LinkedBlocks, OnlyTheBlocksThePairsNameRenumberedTheFirstStillFixed) {
    reassembly::AssemblyProblem whole;
    for (const char* id : {"a", "b", "c", "d"}) whole.blocks.push_back({.id = id});
    whole.contacts = {{{2, 1}, {1, 4}}};
    whole.colinear = {{{1, 0, 1}, {2, 3, 4}}};
    LinkedBlocks two = linked_blocks(whole);
    EXPECT_EQ(two.blocks, (std::vector<std::size_t>{2, 1}));
    ASSERT_EQ(two.problem.blocks.size(), 2u);
    EXPECT_EQ(two.problem.blocks[0].id, "c");
    EXPECT_EQ(two.problem.contacts[0].a.block, 0);
    EXPECT_EQ(two.problem.contacts[0].b.block, 1);
    EXPECT_EQ(two.problem.contacts[0].b.face, 4);
    EXPECT_EQ(two.problem.colinear[0].a.block, 1);
    EXPECT_EQ(two.problem.colinear[0].b.face_b, 4);
    EXPECT_TRUE(two.problem.fixed.empty());  // its first block, c, stays still

    whole.contacts.push_back({{3, 0}, {0, 2}});  // the folder's first block is linked
    LinkedBlocks three = linked_blocks(whole);
    EXPECT_EQ(three.blocks, (std::vector<std::size_t>{0, 2, 1, 3}));
    EXPECT_EQ(three.problem.contacts[1].b.block, 0);

    whole.fixed = {3};
    EXPECT_EQ(linked_blocks(whole).blocks.front(), 3u);
    EXPECT_EQ(linked_blocks(whole).problem.fixed, (std::vector<int>{0}));
}

}  // namespace
}  // namespace anascan::acquisition
