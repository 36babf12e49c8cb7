// CampaignStore: reading and writing the scans, pairs, stones and values.
#include <algorithm>
#include <cstring>

#include "campaign/store_impl.hpp"

namespace anascan::acquisition {
namespace {

std::vector<std::uint64_t> keys_from(const std::vector<unsigned char>& bytes) {
    std::vector<std::uint64_t> keys(bytes.size() / sizeof(std::uint64_t));
    if (!keys.empty()) std::memcpy(keys.data(), bytes.data(), keys.size() * sizeof(std::uint64_t));
    return keys;
}

std::string ids_json(const std::vector<std::int64_t>& ids) {
    std::string out = "[";
    for (std::size_t i = 0; i < ids.size(); ++i) {
        out += (i ? "," : "") + std::to_string(ids[i]);
    }
    return out + "]";
}

std::vector<std::int64_t> ids_from(const std::string& json) {
    std::vector<std::int64_t> ids;
    const char* p = json.c_str();
    while (*p != '\0') {
        char* end = nullptr;
        const long long v = std::strtoll(p, &end, 10);
        if (end != p) {
            ids.push_back(v);
            p = end;
        } else {
            ++p;
        }
    }
    return ids;
}

Expected<void> write_scan(db::Connection& db, const CampaignScanRow& row) {
    auto stmt = db::Statement::prepare(
        db, "UPDATE scans SET state = ?, problem = ?, summary_json = ?, keys = ? WHERE id = ?");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, std::string_view(row.state))
        .bind(2, std::string_view(row.problem))
        .bind(3, std::string_view(row.summary_json))
        .bind_blob(4, row.keys.data(), row.keys.size() * sizeof(std::uint64_t))
        .bind(5, row.id);
    return stmt->run("cannot record scan " + std::to_string(row.id));
}

/// A table whose rows contradict each other (a damaged database that SQLite's own checks
/// pass): readers index scans by id, so this is found before anything uses the rows.
Error damaged_table(const std::filesystem::path& dir, const std::string& table,
                    const std::string& problem) {
    return Error{ErrorCode::kFormat,
                 (dir / "campaign.sqlite").string() + ": the " + table +
                     " table is damaged: " + problem +
                     " (restore the campaign folder from a copy, or start it again with "
                     "`anascan campaign init`)"};
}

/// The single number a `SELECT COUNT(*) ...` gives.
Expected<std::size_t> count_rows(const db::Connection& db, std::string_view sql) {
    auto stmt = db::Statement::prepare(db, sql);
    if (!stmt) return fail(stmt.error());
    auto row = stmt->step("cannot count rows");
    if (!row) return fail(row.error());
    return static_cast<std::size_t>(*row ? std::max<std::int64_t>(0, stmt->int64(0)) : 0);
}

Expected<std::size_t> scan_count(const db::Connection& db) {
    return count_rows(db, "SELECT COUNT(*) FROM scans");
}

bool is_scan(std::int64_t id, std::size_t count) {
    return id >= 0 && static_cast<std::size_t>(id) < count;
}

}  // namespace

Expected<std::vector<CampaignScanRow>> CampaignStore::scans() const {
    auto rows = db::collect(
        impl_->db, "SELECT id, file, state, problem, summary_json, keys FROM scans ORDER BY id",
        "cannot read the scans", [](const db::Statement& s) {
            return CampaignScanRow{.id = s.int64(0),
                                   .file = s.text(1),
                                   .state = s.text(2),
                                   .problem = s.text(3),
                                   .summary_json = s.text(4),
                                   .keys = keys_from(s.blob(5))};
        });
    if (!rows) return rows;
    for (std::size_t i = 0; i < rows->size(); ++i) {
        if ((*rows)[i].id == static_cast<std::int64_t>(i)) continue;
        return fail(damaged_table(impl_->dir, "scans",
                                  "row " + std::to_string(i) + " holds scan id " +
                                      std::to_string((*rows)[i].id) + " (ids run 0..N-1)"));
    }
    return rows;
}

Expected<void> CampaignStore::save_scan(const CampaignScanRow& row) {
    return write_scan(impl_->db, row);
}

Expected<void> CampaignStore::save_scans(const std::vector<CampaignScanRow>& rows) {
    auto tx = db::Transaction::begin(impl_->db);
    if (!tx) return fail(tx.error());
    for (const CampaignScanRow& row : rows) {
        if (auto ok = write_scan(impl_->db, row); !ok) return ok;
    }
    return tx->commit();
}

Expected<std::vector<CampaignPairRow>> CampaignStore::pairs() const {
    auto count = scan_count(impl_->db);
    if (!count) return fail(count.error());
    auto rows = db::collect(
        impl_->db,
        "SELECT source, target, similarity, result_json FROM pairs ORDER BY source, target",
        "cannot read the pairs", [](const db::Statement& s) {
            return CampaignPairRow{.source = s.int64(0),
                                   .target = s.int64(1),
                                   .similarity = s.real(2),
                                   .result_json = s.text(3)};
        });
    if (!rows) return rows;
    // The key's columns take any SQLite type: 2.5 or '2' would read as scan 2 yet match no
    // `WHERE source = 2`, so a repair could not reach the row.
    auto odd = count_rows(impl_->db,
                          "SELECT COUNT(*) FROM pairs WHERE typeof(source) != 'integer' OR "
                          "typeof(target) != 'integer'");
    if (!odd) return fail(odd.error());
    if (*odd > 0) {
        return fail(damaged_table(impl_->dir, "pairs",
                                  std::to_string(*odd) +
                                      " pair(s) name a scan by a value that is not a whole "
                                      "number"));
    }
    for (const CampaignPairRow& p : *rows) {
        if (is_scan(p.source, *count) && is_scan(p.target, *count) && p.source != p.target)
            continue;
        return fail(damaged_table(impl_->dir, "pairs",
                                  "pair " + std::to_string(p.source) + "-" +
                                      std::to_string(p.target) + " does not name two of the " +
                                      std::to_string(*count) + " scans"));
    }
    return rows;
}

Expected<void> CampaignStore::set_candidates(const std::vector<CampaignPairRow>& pairs) {
    auto tx = db::Transaction::begin(impl_->db);
    if (!tx) return fail(tx.error());
    for (const CampaignPairRow& p : pairs) {
        auto stmt = db::Statement::prepare(
            impl_->db, "INSERT INTO pairs(source, target, similarity) VALUES(?, ?, ?)");
        if (!stmt) return fail(stmt.error());
        stmt->bind(1, p.source).bind(2, p.target).bind(3, p.similarity);
        if (auto ok = stmt->run("cannot record the candidate pairs"); !ok) return ok;
    }
    return tx->commit();
}

Expected<void> CampaignStore::save_pair_result(std::int64_t source, std::int64_t target,
                                               const std::string& result_json) {
    auto stmt = db::Statement::prepare(
        impl_->db, "UPDATE pairs SET result_json = ? WHERE source = ? AND target = ?");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, std::string_view(result_json)).bind(2, source).bind(3, target);
    return stmt->run("cannot record pair " + std::to_string(source) + "-" + std::to_string(target));
}

Expected<std::vector<CampaignStoneRow>> CampaignStore::stones() const {
    auto count = scan_count(impl_->db);
    if (!count) return fail(count.error());
    auto rows = db::collect(impl_->db, "SELECT id, scans_json, result_json FROM stones ORDER BY id",
                            "cannot read the stones", [](const db::Statement& s) {
                                return CampaignStoneRow{.id = s.int64(0),
                                                        .scans = ids_from(s.text(1)),
                                                        .result_json = s.text(2)};
                            });
    if (!rows) return rows;
    for (const CampaignStoneRow& stone : *rows) {
        for (std::int64_t id : stone.scans) {
            if (is_scan(id, *count)) continue;
            return fail(damaged_table(impl_->dir, "stones",
                                      "stone " + std::to_string(stone.id) + " names scan " +
                                          std::to_string(id) + " of " + std::to_string(*count)));
        }
    }
    return rows;
}

Expected<void> CampaignStore::set_stones(const std::vector<CampaignStoneRow>& stones,
                                         const std::string& graph_json) {
    auto tx = db::Transaction::begin(impl_->db);
    if (!tx) return fail(tx.error());
    for (const CampaignStoneRow& stone : stones) {
        auto stmt =
            db::Statement::prepare(impl_->db, "INSERT INTO stones(id, scans_json) VALUES(?, ?)");
        if (!stmt) return fail(stmt.error());
        stmt->bind(1, stone.id).bind(2, std::string_view(ids_json(stone.scans)));
        if (auto ok = stmt->run("cannot record the stones"); !ok) return ok;
    }
    auto value = db::Statement::prepare(
        impl_->db, "INSERT OR REPLACE INTO campaign_values(key, json) VALUES('graph', ?)");
    if (!value) return fail(value.error());
    value->bind(1, std::string_view(graph_json));
    if (auto ok = value->run("cannot record the match graph"); !ok) return ok;
    return tx->commit();
}

Expected<void> CampaignStore::save_stone_result(std::int64_t id, const std::string& result_json) {
    auto stmt = db::Statement::prepare(impl_->db, "UPDATE stones SET result_json = ? WHERE id = ?");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, std::string_view(result_json)).bind(2, id);
    return stmt->run("cannot record stone " + std::to_string(id));
}

Expected<void> CampaignStore::clear_stones() {
    auto tx = db::Transaction::begin(impl_->db);
    if (!tx) return fail(tx.error());
    for (const char* sql :
         {"DELETE FROM stones", "DELETE FROM campaign_values WHERE key = 'graph'"}) {
        auto stmt = db::Statement::prepare(impl_->db, sql);
        if (!stmt) return fail(stmt.error());
        if (auto ok = stmt->run("cannot clear the stones"); !ok) return ok;
    }
    return tx->commit();
}

Expected<std::string> CampaignStore::integrity_check() const {
    return db::integrity_check(impl_->db);
}

Expected<std::optional<std::string>> CampaignStore::value(const std::string& key) const {
    auto stmt = db::Statement::prepare(impl_->db, "SELECT json FROM campaign_values WHERE key = ?");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, std::string_view(key));
    auto row = stmt->step("cannot read " + key);
    if (!row) return fail(row.error());
    if (!*row) return std::optional<std::string>();
    return std::optional<std::string>(stmt->text(0));
}

Expected<void> CampaignStore::set_value(const std::string& key, const std::string& json) {
    auto stmt = db::Statement::prepare(
        impl_->db, "INSERT OR REPLACE INTO campaign_values(key, json) VALUES(?, ?)");
    if (!stmt) return fail(stmt.error());
    stmt->bind(1, std::string_view(key)).bind(2, std::string_view(json));
    return stmt->run("cannot record " + key);
}

}  // namespace anascan::acquisition
