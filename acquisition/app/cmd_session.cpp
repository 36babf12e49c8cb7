// anascan session ...: look at, check, export and annotate a capture session folder.
#include <cstdio>

#include "commands.hpp"
#include "session_cli.hpp"

namespace anascan::cli {

using acquisition::SessionOpenMode;

std::unique_ptr<acquisition::SessionStore> open_session(const std::filesystem::path& dir,
                                                        SessionOpenMode mode) {
    auto store = acquisition::SessionStore::open(dir, mode);
    if (!store) fail_command(store.error());
    return std::move(*store);
}

namespace {

struct ActionOptions {
    std::string dir;
    std::int64_t seq = 0;
    bool undo = false;
    std::optional<std::int64_t> note_seq;
    std::string text;
};

void add_dir(CLI::App* cmd, ActionOptions& o) {
    cmd->add_option("dir", o.dir, "Session folder")->required();
}

void add_exclude(CLI::App& session) {
    auto o = std::make_shared<ActionOptions>();
    auto* cmd = session.add_subcommand(
        "exclude", "Exclude a scan from the model (kept on disk; --undo brings it back)");
    add_dir(cmd, *o);
    cmd->add_option("seq", o->seq, "Scan sequence number")->required();
    cmd->add_flag("--undo", o->undo, "Include the scan again");
    cmd->callback([o] {
        auto store = open_session(o->dir, SessionOpenMode::kEdit);
        if (auto ok = store->set_excluded(o->seq, !o->undo); !ok) fail_command(ok.error());
        (void)store->add_event(o->undo ? "included" : "excluded", "",
                               "scan " + std::to_string(o->seq) + " by the operator");
        std::printf("scan %lld %s\n", static_cast<long long>(o->seq),
                    o->undo ? "included again" : "excluded (kept on disk)");
    });
}

void add_note(CLI::App& session) {
    auto o = std::make_shared<ActionOptions>();
    auto* cmd = session.add_subcommand("note", "Add an operator note to the session");
    add_dir(cmd, *o);
    cmd->add_option("text", o->text, "The note")->required();
    cmd->add_option("--scan", o->note_seq, "The scan the note is about");
    cmd->callback([o] {
        auto store = open_session(o->dir, SessionOpenMode::kEdit);
        if (auto ok = store->add_note(o->note_seq, o->text); !ok) fail_command(ok.error());
        std::printf("note added%s\n",
                    o->note_seq ? (" to scan " + std::to_string(*o->note_seq)).c_str() : "");
    });
}

void add_turned_over(CLI::App& session) {
    auto o = std::make_shared<ActionOptions>();
    auto* cmd = session.add_subcommand(
        "turned-over",
        "Mark that the stone was turned over after scan SEQ (registration opens "
        "a new group and merges it on the stone alone)");
    add_dir(cmd, *o);
    cmd->add_option("--after", o->seq, "Last scan before turning the stone over")->required();
    cmd->callback([o] {
        auto store = open_session(o->dir, SessionOpenMode::kEdit);
        if (auto ok = store->mark_turned_over(o->seq); !ok) fail_command(ok.error());
        std::printf("stone turned over after scan %lld\n", static_cast<long long>(o->seq));
    });
}

}  // namespace

void add_session_command(CLI::App& app) {
    auto* session = app.add_subcommand(
        "session", "Look at, check, export and annotate a capture session folder");
    session->require_subcommand(1);
    add_session_info_commands(*session);
    add_session_export_command(*session);
    add_session_register_command(*session);
    add_session_consistency_command(*session);
    add_exclude(*session);
    add_note(*session);
    add_turned_over(*session);
}

}  // namespace anascan::cli
