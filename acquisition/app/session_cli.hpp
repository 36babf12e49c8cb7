#pragma once
// Shared by the `anascan session ...` commands.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>

#include "anascan/acquisition/store/session_store.hpp"

namespace anascan::cli {

/// Opens the session or throws CommandFailed with the store's message.
std::unique_ptr<acquisition::SessionStore> open_session(const std::filesystem::path& dir,
                                                        acquisition::SessionOpenMode mode);

/// `session info`, `session check` (registered on the `session` group).
void add_session_info_commands(CLI::App& session);
/// `session register` (registers a session again; re-registers chosen scans).
void add_session_register_command(CLI::App& session);
/// `session consistency` (the model's scans checked against each other).
void add_session_consistency_command(CLI::App& session);
/// `session export`.
void add_session_export_command(CLI::App& session);

}  // namespace anascan::cli
