// libFuzzer harness for the session database's contents: a valid session (two scans, a
// registration, an event, a note, a value, a turn-over) is written once; each input then
// rewrites, copies or deletes rows of any table of a fresh copy, with hostile values of any
// SQLite type, and the copy is opened read-only, listed, loaded, shown as JSON and checked,
// with and without repair. Nothing may crash, leak or hang; every error carries a message.
// The edits: sqlite_fuzz_edits.hpp.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "anascan/acquisition/store/session_check.hpp"
#include "anascan/acquisition/store/session_json.hpp"
#include "anascan/acquisition/store/session_store.hpp"
#include "sqlite_fuzz_edits.hpp"

namespace {

namespace fs = std::filesystem;
using namespace anascan;
using namespace anascan::acquisition;
using namespace anascan::fuzz;

Scan small_scan(unsigned seed) {
    Scan scan;
    scan.meta.device_id = "sim:structured-light#0";
    scan.meta.device_kind = DeviceKind::kStructuredLight;
    scan.meta.sensor_origin_scan_m = Eigen::Vector3d(0, 0, 1);
    for (unsigned i = 0; i < 40; ++i)
        scan.cloud.positions.emplace_back(0.01f * float(i % 7), 0.01f * float(i / 7),
                                          0.001f * float(seed));
    return scan;
}

void write_template(const fs::path& dir) {
    auto store = SessionStore::open(dir, SessionOpenMode::kCreateOrOpen);
    require(bool(store));
    SessionStore& s = **store;
    require(bool(s.save_scan(small_scan(1), Pose::Identity())));
    require(bool(s.save_scan(small_scan(2), std::nullopt)));
    RegistrationUpdate update;
    update.group = 0;
    update.pose = Pose::Identity();
    update.quality_json = R"({"rms_mm":0.1,"overlap":0.9})";
    update.latency_s = 0.5;
    require(bool(s.record_registration(1, update)));
    require(bool(s.add_event("merge", "sim:structured-light#0", "groups 1 and 0 merged")));
    require(bool(s.add_note(2, "chipped corner")));
    require(bool(s.set_value("coverage", R"({"fraction":0.5,"area_m2":0.2})")));
    require(bool(s.mark_turned_over(1)));
    require(bool(s.checkpoint()));
}

void read_everything(const fs::path& dir) {
    auto store = SessionStore::open(dir, SessionOpenMode::kReadOnly);
    require_message(store);
    if (!store) return;
    const SessionStore& s = **store;
    const auto scans = s.scans();
    require_message(scans);
    if (scans) {
        for (const ScanRecord& r : *scans) require_message(s.load_scan(r.seq));
    }
    require_message(s.events());
    require_message(s.notes());
    require_message(s.devices());
    require_message(s.value("coverage"));
    require_message(session_info_json(s));
    require_message(coverage_fraction(s));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const Workspace& w = workspace("session", write_template);
    write_tree(w.work, w.image);
    edit_database(w.work / "session.sqlite", Reader{{data, size}});
    read_everything(w.work);
    require_message(check_session(w.work));
    require_message(check_session(w.work, {.repair = true}));
    read_everything(w.work);
    return 0;
}
