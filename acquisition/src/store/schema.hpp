#pragma once
// The session database schema: a list of migrations, version N turning a version N-1
// database into version N. `PRAGMA user_version` holds the version; the `migrations` table
// records when each step was applied.
#include <string_view>

#include "store/db.hpp"

namespace anascan::acquisition::db {

/// SQL of the migration to `version` (1 = the first schema); empty when unknown.
std::string_view migration_sql(int version);

/// Brings the database to kSessionSchemaVersion, one transaction per step. A database of
/// a newer version is refused with an error naming the file; `read_only` refuses to
/// migrate an older one (it says how to upgrade).
Expected<void> migrate(Connection& db, bool read_only);

/// The database's `PRAGMA user_version`.
Expected<int> schema_version(const Connection& db);

}  // namespace anascan::acquisition::db
