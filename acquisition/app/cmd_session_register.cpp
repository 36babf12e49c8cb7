// anascan session register DIR [--scan SEQ ...]: registers a session again after the fact
// (all scans in capture order, as a resumed capture does), then places the given scans again
// by global registration (the operator's "re-register" for scans that look wrong).
#include <cstdio>

#include "anascan/acquisition/capture/capture_session.hpp"
#include "capture_summary.hpp"
#include "commands.hpp"
#include "session_cli.hpp"

namespace anascan::cli {
namespace {

struct RegisterOptions {
    std::string dir;
    std::vector<std::int64_t> scans;
};

void run_session_register(const RegisterOptions& o) {
    auto store = open_session(o.dir, acquisition::SessionOpenMode::kOpenExisting);
    for (const std::int64_t seq : o.scans) {  // Before the session's scans are registered.
        auto record = store->scan(seq);
        if (!record) fail_command(record.error());
        if (record->excluded)
            throw CommandFailed(o.dir + ": scan " + std::to_string(seq) +
                                " is excluded: include it first (anascan session exclude " + o.dir +
                                " " + std::to_string(seq) + " --undo)");
    }
    auto session = acquisition::CaptureSession::start(std::move(store), {}, printing_sink());
    if (!session) fail_command(session.error());
    // Queued after the session's own scans: each is placed again once the model exists.
    for (const std::int64_t seq : o.scans) {
        if (auto ok = (*session)->reregister(seq); !ok) fail_command(ok.error());
    }
    (*session)->wait_until_idle();
    store_final_coverage((*session)->store());
    print_capture_summary((*session)->store());
}

}  // namespace

void add_session_register_command(CLI::App& session) {
    auto o = std::make_shared<RegisterOptions>();
    auto* cmd = session.add_subcommand(
        "register",
        "Register the session's scans again (in capture order, as a resumed capture does), "
        "then register each --scan again by global registration; prints each result");
    cmd->add_option("dir", o->dir, "Session folder")->required();
    cmd->add_option("--scan", o->scans, "A scan to register again (repeatable)");
    cmd->callback([o] { run_session_register(*o); });
}

}  // namespace anascan::cli
