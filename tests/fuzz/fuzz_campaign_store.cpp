// libFuzzer harness for the campaign store's contents: a small finished campaign
// (campaign_template.hpp) is written once; each input may first truncate one prepared cloud,
// then rewrites, copies or deletes rows of any table of a fresh copy with hostile values of any
// SQLite type (sqlite_fuzz_edits.hpp). The copy is then read as `campaign status` and the job
// read it, and checked, with and without repair. Nothing may crash, leak or hang; every error
// carries a message; and once `check --repair` reports the campaign clean, status and the
// job's reading of the stored results must succeed.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "anascan/acquisition/campaign/campaign_check.hpp"
#include "anascan/acquisition/campaign/campaign_results.hpp"
#include "anascan/acquisition/campaign/campaign_store.hpp"
#include "campaign/campaign_json.hpp"
#include "campaign_template.hpp"
#include "sqlite_fuzz_edits.hpp"

namespace {

namespace fs = std::filesystem;
using namespace anascan;
using namespace anascan::acquisition;
using namespace anascan::fuzz;

/// One byte: a multiple of 4 truncates the prepared cloud of scan (byte / 4) % 4 to half.
void damage_prepared(const fs::path& dir, std::uint8_t byte) {
    if (byte % 4 != 0) return;
    const fs::path file = dir / "prepared" / ("scan_" + std::to_string((byte / 4) % 4) + ".ply");
    std::error_code ec;
    const auto size = fs::file_size(file, ec);
    if (!ec) fs::resize_file(file, size / 2, ec);
}

/// Reads the campaign as `campaign status` and the job do; what failed (empty: all of it
/// reads).
std::string read_everything(const fs::path& dir) {
    auto store = CampaignStore::open(dir, true);
    require_message(store);
    if (!store) return store.error().message;
    const auto scans = (*store)->scans();
    require_message(scans);
    require_message((*store)->pairs());
    require_message((*store)->stones());
    require_message((*store)->value("graph"));
    const auto status = campaign_status(**store);
    require_message(status);
    if (!scans) return scans.error().message;
    const auto stored = campaign_json::verify_stored(**store, *scans);
    require_message(stored);
    if (!status) return status.error().message;
    if (!stored) return stored.error().message;
    return {};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const Workspace& w = workspace("campaign", test::write_campaign_template);
    write_tree(w.work, w.image);
    Reader in{{data, size}};
    damage_prepared(w.work, in.byte());
    edit_database(w.work / "campaign.sqlite", in);
    read_everything(w.work);
    require_message(check_campaign(w.work, false));
    const auto repaired = check_campaign(w.work, true);
    require_message(repaired);
    const std::string failed = read_everything(w.work);
    if (repaired && repaired->clean() && !failed.empty()) {
        std::fprintf(stderr, "check --repair said clean, yet: %s\n", failed.c_str());
        require(false);
    }
    return 0;
}
