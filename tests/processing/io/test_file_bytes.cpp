#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "anascan/processing/io/file_bytes.hpp"

namespace anascan::io {
namespace {

namespace fs = std::filesystem;

std::vector<char> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

// A fresh folder in the build tree per test, removed afterwards.
class FileBytes : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::path(ANASCAN_BINARY_DIR) / "test-tmp" / "file_bytes" / info->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ignored);
        fs::remove_all(dir_, ignored);
    }
    std::size_t entries_in(const fs::path& dir) const {
        return static_cast<std::size_t>(
            std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
    }
    fs::path dir_;
};

TEST_F(FileBytes, ReadingAMissingFileNamesIt) {
    const fs::path missing = dir_ / "no-such-scan.ply";
    const auto result = read_file_bytes(missing);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, ErrorCode::kIo);
    EXPECT_NE(result.error().message.find(missing.string()), std::string::npos)
        << result.error().message;
}

TEST_F(FileBytes, ReadingADirectoryIsAnError) {
    const auto result = read_file_bytes(dir_);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, ErrorCode::kIo);
    EXPECT_NE(result.error().message.find("directory"), std::string::npos)
        << result.error().message;
}

TEST_F(FileBytes, WriteThenReadRoundTrip) {
    std::vector<char> data;
    for (int i = 0; i < 100000; ++i) data.push_back(static_cast<char>(i * 7 % 256));
    const fs::path file = dir_ / "binary.bin";
    ASSERT_TRUE(write_file_atomically(file, data));
    const auto read = read_file_bytes(file);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(*read, data);
    EXPECT_EQ(entries_in(dir_), 1u);  // No temporary file left behind.
}

TEST_F(FileBytes, EmptyFileRoundTrip) {
    const fs::path file = dir_ / "empty.txt";
    ASSERT_TRUE(write_file_atomically(file, {}));
    const auto read = read_file_bytes(file);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_TRUE(read->empty());
}

TEST_F(FileBytes, OverwritingReplacesTheWholeContent) {
    const fs::path file = dir_ / "session.json";
    ASSERT_TRUE(write_file_atomically(file, bytes_of("old content that is rather long")));
    ASSERT_TRUE(write_file_atomically(file, bytes_of("new")));
    const auto read = read_file_bytes(file);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(*read, bytes_of("new"));
    EXPECT_EQ(entries_in(dir_), 1u);
}

TEST_F(FileBytes, ReadOnlyFolderGivesAnErrorAndKeepsTheOldFile) {
    const fs::path file = dir_ / "scan.ply";
    ASSERT_TRUE(write_file_atomically(file, bytes_of("old")));
    fs::permissions(dir_, fs::perms::owner_read | fs::perms::owner_exec);
    {
        // Root (or a capability) ignores permissions: then there is nothing to test.
        std::ofstream probe(dir_ / "probe");
        if (probe) {
            probe.close();
            fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add);
            GTEST_SKIP() << "running with permission overrides (root?): read-only folders "
                            "cannot be simulated";
        }
    }
    const auto result = write_file_atomically(file, bytes_of("new content"));
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, ErrorCode::kIo);
    EXPECT_NE(result.error().message.find(file.string()), std::string::npos)
        << result.error().message;
    EXPECT_EQ(entries_in(dir_), 1u);  // No temporary file left behind.
    const auto read = read_file_bytes(file);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(*read, bytes_of("old"));
}

TEST_F(FileBytes, MissingParentFolderGivesAnErrorNamingTheFile) {
    const fs::path file = dir_ / "no-such-folder" / "scan.ply";
    const auto result = write_file_atomically(file, bytes_of("data"));
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, ErrorCode::kIo);
    EXPECT_NE(result.error().message.find(file.string()), std::string::npos)
        << result.error().message;
    EXPECT_FALSE(fs::exists(file.parent_path()));
    EXPECT_EQ(entries_in(dir_), 0u);
}

}  // namespace
}  // namespace anascan::io
