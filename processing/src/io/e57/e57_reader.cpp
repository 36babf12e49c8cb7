#include <filesystem>

#include "anascan/processing/io/e57.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "paged_file.hpp"
#include "scan_decoder.hpp"
#include "schema.hpp"
#include "xml_tree.hpp"

namespace anascan::io {

Expected<E57File> parse_e57(std::span<const char> bytes, std::string_view source_name) {
    auto file = e57::PagedFile::open(bytes, source_name);
    if (!file) return fail(file.error());
    const e57::FileHeader& h = file->header();
    auto xml = file->read(h.xml_physical_offset, h.xml_logical_length, "the XML section");
    if (!xml) return fail(xml.error());
    const e57::XmlSource where{source_name, h.xml_physical_offset};
    auto root = e57::parse_xml(*xml, where);
    if (!root) return fail(root.error());
    auto spec = e57::read_file_spec(*root, where);
    if (!spec) return fail(spec.error());
    if (spec->scans.empty()) {
        return fail(where.error(ErrorCode::kEmpty, 0, "no scan (data3D entry) in the file"));
    }
    E57File out{.guid = spec->guid, .image_count = spec->image_count};
    for (std::size_t i = 0; i < spec->scans.size(); ++i) {
        auto scan = e57::decode_scan(*file, spec->scans[i], i);
        if (!scan) return fail(scan.error());
        out.scans.push_back(std::move(*scan));
    }
    return out;
}

Expected<E57File> read_e57(const std::filesystem::path& path) {
    const Expected<std::vector<char>> bytes = read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    return parse_e57(*bytes, path.filename().string());
}

}  // namespace anascan::io
