#include <cstdio>
#include <random>

#include "anascan/processing/io/e57.hpp"
#include "anascan/processing/io/file_bytes.hpp"
#include "file_writer.hpp"
#include "io/text_lines.hpp"
#include "paged_file.hpp"

namespace anascan::io {
namespace {

// Text as CDATA; a "]]>" inside is split across two CDATA sections.
std::string cdata(std::string_view text) {
    std::string out = "<![CDATA[";
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text.substr(i, 3) == "]]>") {
            out += "]]]]><![CDATA[>";
            i += 2;
        } else {
            out += text[i];
        }
    }
    return out + "]]>";
}

std::string element(std::string_view name, std::string_view type, std::string_view value) {
    return "<" + std::string(name) + " type=\"" + std::string(type) + "\">" + std::string(value) +
           "</" + std::string(name) + ">";
}

std::string float_element(std::string_view name, double v) {
    return element(name, "Float", text::format_exact(v));
}

std::string new_guid() {
    std::random_device entropy;
    char text[40];
    std::snprintf(text, sizeof text, "{%08X-%04X-%04X-%04X-%04X%08X}", entropy(),
                  entropy() & 0xFFFFu, (entropy() & 0x0FFFu) | 0x4000u,
                  (entropy() & 0x3FFFu) | 0x8000u, entropy() & 0xFFFFu, entropy());
    return text;
}

std::string pose_xml(const Pose& T) {
    const Eigen::Quaterniond q(T.linear());
    const Eigen::Vector3d t = T.translation();
    return "<pose type=\"Structure\"><rotation type=\"Structure\">" + float_element("w", q.w()) +
           float_element("x", q.x()) + float_element("y", q.y()) + float_element("z", q.z()) +
           "</rotation><translation type=\"Structure\">" + float_element("x", t.x()) +
           float_element("y", t.y()) + float_element("z", t.z()) + "</translation></pose>";
}

std::string scan_xml(const e57::ScanSection& scan, std::uint64_t section_offset) {
    std::string out = "<vectorChild type=\"Structure\">";
    out += element("guid", "String", cdata(scan.guid.empty() ? new_guid() : scan.guid));
    out += element("name", "String", cdata(scan.name));
    if (scan.T_file_scan) out += pose_xml(*scan.T_file_scan);
    out += scan.extra_xml;
    out += "<points type=\"CompressedVector\" fileOffset=\"" + std::to_string(section_offset) +
           "\" recordCount=\"" + std::to_string(scan.announced_count.value_or(scan.record_count)) +
           "\">";
    out += e57::prototype_xml(scan.fields);
    out += "<codecs type=\"Vector\" allowHeterogeneousChildren=\"1\"/></points></vectorChild>";
    return out;
}

std::string color_limits_xml() {
    std::string out = "<colorLimits type=\"Structure\">";
    for (const char* c : {"Red", "Green", "Blue"}) {
        out += element(std::string("color") + c + "Minimum", "Integer", "0");
        out += element(std::string("color") + c + "Maximum", "Integer", "255");
    }
    return out + "</colorLimits>";
}

std::string root_xml(const std::string& scans_xml) {
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
           "<e57Root type=\"Structure\" xmlns=\"http://www.astm.org/COMMIT/E57/2010-e57-v1.0\">" +
           element("formatName", "String", cdata("ASTM E57 3D Imaging Data File")) +
           element("guid", "String", cdata(new_guid())) + element("versionMajor", "Integer", "1") +
           element("versionMinor", "Integer", "0") +
           element("e57LibraryVersion", "String", cdata("anascan")) +
           "<coordinateMetadata type=\"String\"/>"
           "<data3D type=\"Vector\" allowHeterogeneousChildren=\"1\">" +
           scans_xml +
           "</data3D><images2D type=\"Vector\" allowHeterogeneousChildren=\"1\"/></e57Root>\n";
}

void put_u32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b[at + i] = std::uint8_t(v >> (8 * i));
}

void put_u64(std::vector<std::uint8_t>& b, std::size_t at, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) b[at + i] = std::uint8_t(v >> (8 * i));
}

// The 48-byte file header, written once the XML's place and the file's length are known.
void write_header(std::vector<std::uint8_t>& logical, std::uint64_t xml_logical,
                  std::uint64_t xml_length) {
    const std::uint64_t pages = (logical.size() + e57::kPageDataBytes - 1) / e57::kPageDataBytes;
    const char* signature = "ASTM-E57";
    std::copy(signature, signature + 8, logical.begin());
    put_u32(logical, 8, 1);
    put_u32(logical, 12, 0);
    put_u64(logical, 16, pages * e57::kPageBytes);
    put_u64(logical, 24, e57::to_physical(xml_logical));
    put_u64(logical, 32, xml_length);
    put_u64(logical, 40, e57::kPageBytes);
}

}  // namespace

namespace e57 {

std::vector<char> assemble_file(std::span<const ScanSection> scans) {
    std::vector<std::uint8_t> logical(kHeaderBytes, 0);
    std::string scans_xml;
    for (const ScanSection& scan : scans) {
        const std::uint64_t offset = append_section(logical, scan.fields, scan.record_count);
        scans_xml += scan_xml(scan, offset);
    }
    const std::string xml = root_xml(scans_xml);
    const std::uint64_t xml_logical = logical.size();
    logical.insert(logical.end(), xml.begin(), xml.end());
    write_header(logical, xml_logical, xml.size());
    return paginate(logical);
}

}  // namespace e57

Expected<std::vector<char>> encode_e57(std::span<const E57Scan> scans) {
    std::vector<e57::ScanSection> sections;
    for (const E57Scan& scan : scans) {
        auto fields = e57::encode_fields(scan);
        if (!fields) return fail(fields.error());
        sections.push_back({.name = scan.name.empty() ? scan.scan.meta.id : scan.name,
                            .guid = scan.guid,
                            .T_file_scan = scan.scan.meta.T_world_scan,
                            .extra_xml = scan.scan.cloud.has_colors() ? color_limits_xml() : "",
                            .fields = std::move(*fields),
                            .record_count = scan.scan.cloud.size()});
    }
    return e57::assemble_file(sections);
}

Expected<void> write_e57(const std::filesystem::path& path, std::span<const E57Scan> scans) {
    auto bytes = encode_e57(scans);
    if (!bytes) return fail(bytes.error());
    return write_file_atomically(path, *bytes);
}

}  // namespace anascan::io
