// libFuzzer harness for the files of a blocks folder as the matcher, the assembly and the
// field app read them: the input is read as a block's features file (`ID.features.json`)
// and, if it reads, matched against a copy of itself (every score computed on its values);
// the folder holding it is opened and the expert's links parsed against it; and the same
// bytes are read as a proposals file of `blocks match`. Nothing may crash, leak or hang;
// every error carries a message.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "anascan/acquisition/blocks/block_features_file.hpp"
#include "anascan/acquisition/blocks/block_folder.hpp"
#include "anascan/acquisition/blocks/block_proposals.hpp"
#include "anascan/processing/reassembly/face_matching.hpp"
#include "fuzz_require.hpp"

namespace {

namespace fs = std::filesystem;
using namespace anascan;
using namespace anascan::acquisition;
using namespace anascan::fuzz;

const fs::path& folder() {
    static const fs::path dir = [] {
        const fs::path d =
            fs::temp_directory_path() / ("anascan-fuzz-blocks-" + std::to_string(getpid()));
        fs::remove_all(d);
        fs::create_directories(d);
        // The other block of the folder, as `blocks features` writes what the folder reads.
        std::ofstream(d / "a.features.json")
            << R"({"id":"a","source":"a.ply","faces":[{"id":0},{"id":1},{"id":2},{"id":3}]})";
        return d;
    }();
    static const bool removed_at_exit = (std::atexit([] {
                                             std::error_code ec;
                                             fs::remove_all(folder(), ec);
                                         }),
                                         true);
    (void)removed_at_exit;
    return dir;
}

void match_with_itself(const NamedBlockFeatures& block) {
    const std::vector<reassembly::BlockFeatures> blocks{block.features, block.features};
    const reassembly::MatchResult r = reassembly::match_blocks(blocks, {}, {});
    for (const auto& pair : r.match_graph) require(pair.a.block != pair.b.block);
}

void parse_links(const BlockFolder& folder) {
    const std::string a = folder.ids.front(), b = folder.ids.back();
    for (const std::string& link : {a + ":0=" + b + ":1", a + ":0/1=" + b + ":2/3",
                                    a + ":99999999999=" + b + ":0", a + ":-1=" + b + ":x"}) {
        require_message(parse_face_link(folder, link));
        require_message(parse_line_link(folder, link));
    }
    AssemblyLinks links{.contacts = {a + ":0=" + b + ":0"}, .fixed = {a}};
    require_message(parse_assembly_links(folder, links));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const fs::path file = folder() / "b.features.json";
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    const auto json = read_json_file(file);
    require_message(json);
    if (json) {
        const auto block = block_features_from_json(*json, file.string());
        require_message(block);
        if (block) match_with_itself(*block);
    }
    const auto opened = open_block_folder(folder());
    require_message(opened);
    if (opened) parse_links(*opened);
    const auto proposals = read_block_proposals(file);
    require_message(proposals);
    if (proposals) accepted_pairs(*proposals);
    return 0;
}
