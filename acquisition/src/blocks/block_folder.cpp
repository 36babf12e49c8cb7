#include "anascan/acquisition/blocks/block_folder.hpp"

#include <algorithm>

#include "anascan/acquisition/blocks/block_features_file.hpp"

namespace anascan::acquisition {
namespace {

namespace fs = std::filesystem;
namespace ra = reassembly;
using nlohmann::json;

// One features file: its block id, model and face count.
Expected<void> read_features_file(const fs::path& f, BlockFolder& out) {
    auto j = read_json_file(f);
    if (!j) return fail(j.error());
    try {
        out.ids.push_back(j->contains("id") ? j->at("id").get<std::string>()
                                            : f.stem().stem().string());
        out.models.push_back(j->at("source").get<std::string>());
        out.face_counts.push_back(j->at("faces").size());
    } catch (const json::exception& e) {
        return fail(ErrorCode::kFormat, f.string() + ": not a features file: " + e.what());
    }
    return {};
}

Expected<void> check_face_listed(const BlockFolder& folder, const ra::FaceRef& r) {
    const std::size_t count = folder.face_counts[std::size_t(r.block)];
    if (r.face >= 0 && std::size_t(r.face) < count) return {};
    return fail(ErrorCode::kInvalidArgument,
                folder.ids[std::size_t(r.block)] + ":" + std::to_string(r.face) +
                    ": no such face (the block has " + std::to_string(count) + ")");
}

Expected<ra::LineRef> parse_line_ref(const BlockFolder& folder, const std::string& whole,
                                     const std::string& s) {
    const auto slash = s.rfind('/');
    if (slash == std::string::npos)
        return fail(ErrorCode::kInvalidArgument,
                    "'" + whole + "': a line is BLOCK:F/G (the edge of faces F, G)");
    auto a = parse_face_ref(folder.ids, s.substr(0, slash));
    if (!a) return fail(a.error());
    try {
        return ra::LineRef{a->block, a->face, std::stoi(s.substr(slash + 1))};
    } catch (const std::exception&) {
        return fail(ErrorCode::kInvalidArgument, "'" + whole + "': the face is not a number");
    }
}

Expected<int> block_index(const BlockFolder& folder, const std::string& id) {
    const auto it = std::find(folder.ids.begin(), folder.ids.end(), id);
    if (it == folder.ids.end())
        return fail(ErrorCode::kInvalidArgument,
                    "fixed block " + id + ": no such block in " + folder.dir.string());
    return int(it - folder.ids.begin());
}

}  // namespace

Expected<BlockFolder> open_block_folder(const fs::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        return fail(ErrorCode::kIo, dir.string() + ": not a folder of block features");
    BlockFolder out{.dir = dir};
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.path().string().ends_with(".features.json")) out.feature_files.push_back(e.path());
    std::sort(out.feature_files.begin(), out.feature_files.end());
    if (out.feature_files.empty())
        return fail(ErrorCode::kIo,
                    dir.string() + ": no ID.features.json (run anascan blocks features)");
    for (const fs::path& f : out.feature_files)
        if (auto ok = read_features_file(f, out); !ok) return fail(ok.error());
    return out;
}

Expected<ra::FaceRef> parse_face_ref(const std::vector<std::string>& ids, const std::string& text) {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos)
        return fail(ErrorCode::kInvalidArgument, "'" + text + "': expected BLOCK:FACE");
    const auto it = std::find(ids.begin(), ids.end(), text.substr(0, colon));
    if (it == ids.end())
        return fail(ErrorCode::kInvalidArgument,
                    "'" + text + "': no block " + text.substr(0, colon));
    try {
        return ra::FaceRef{int(it - ids.begin()), std::stoi(text.substr(colon + 1))};
    } catch (const std::exception&) {
        return fail(ErrorCode::kInvalidArgument, "'" + text + "': the face is not a number");
    }
}

Expected<ra::FaceLink> parse_face_link(const BlockFolder& folder, const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos)
        return fail(ErrorCode::kInvalidArgument, "'" + text + "': expected A:F=B:G");
    auto a = parse_face_ref(folder.ids, text.substr(0, eq));
    if (!a) return fail(a.error());
    auto b = parse_face_ref(folder.ids, text.substr(eq + 1));
    if (!b) return fail(b.error());
    if (a->block == b->block)
        return fail(ErrorCode::kInvalidArgument, "'" + text + "': both faces on one block");
    if (auto ok = check_face_listed(folder, *a); !ok) return fail(ok.error());
    if (auto ok = check_face_listed(folder, *b); !ok) return fail(ok.error());
    return ra::FaceLink{*a, *b};
}

Expected<ra::LineLink> parse_line_link(const BlockFolder& folder, const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos)
        return fail(ErrorCode::kInvalidArgument, "'" + text + "': expected A:F/G=B:H/K");
    auto a = parse_line_ref(folder, text, text.substr(0, eq));
    if (!a) return fail(a.error());
    auto b = parse_line_ref(folder, text, text.substr(eq + 1));
    if (!b) return fail(b.error());
    return ra::LineLink{*a, *b};
}

Expected<ra::AssemblyProblem> parse_assembly_links(const BlockFolder& folder,
                                                   const AssemblyLinks& links) {
    ra::AssemblyProblem p;
    for (const std::string& t : links.contacts) {
        auto l = parse_face_link(folder, t);
        if (!l) return fail(l.error());
        p.contacts.push_back(*l);
    }
    for (const std::string& t : links.coplanar) {
        auto l = parse_face_link(folder, t);
        if (!l) return fail(l.error());
        p.coplanar.push_back(*l);
    }
    for (const std::string& t : links.colinear) {
        auto l = parse_line_link(folder, t);
        if (!l) return fail(l.error());
        p.colinear.push_back(*l);
    }
    for (const std::string& id : links.fixed) {
        auto b = block_index(folder, id);
        if (!b) return fail(b.error());
        p.fixed.push_back(*b);
    }
    return p;
}

}  // namespace anascan::acquisition
