#include <bit>

#include "anascan/processing/io/file_bytes.hpp"
#include "anascan/processing/io/ply.hpp"
#include "ply_body_reader.hpp"
#include "ply_header.hpp"
#include "ply_source.hpp"

namespace anascan::io {
namespace ply_detail {

std::string plural(const std::string& element_name) {
    if (element_name == "vertex") return "vertices";
    return element_name + "s";
}

}  // namespace ply_detail

namespace {

using ply_detail::AsciiSource;
using ply_detail::BinarySource;
using ply_detail::BodyReader;
using ply_detail::PlyHeader;

template <class Source>
Expected<void> read_body(Source source, const PlyHeader& header, std::string_view name,
                         PlyData& data) {
    BodyReader<Source> reader(source, header, name, data);
    return reader.read_all();
}

Expected<void> read_body(std::span<const char> bytes, const PlyHeader& header,
                         std::string_view name, PlyData& data) {
    constexpr bool kLittleHost = std::endian::native == std::endian::little;
    const std::size_t start = header.body_offset;
    switch (header.format) {
        case PlyFormat::kAscii:
            return read_body(AsciiSource(bytes, start, header.body_line), header, name, data);
        case PlyFormat::kBinaryLittleEndian:
            return read_body(BinarySource<!kLittleHost>(bytes, start), header, name, data);
        case PlyFormat::kBinaryBigEndian:
            return read_body(BinarySource<kLittleHost>(bytes, start), header, name, data);
    }
    return {};
}

}  // namespace

Expected<PlyData> parse_ply(std::span<const char> bytes, std::string_view source_name) {
    Expected<PlyHeader> header = ply_detail::parse_ply_header(bytes, source_name);
    if (!header) return fail(header.error());
    PlyData data;
    data.format = header->format;
    data.comments = std::move(header->comments);
    if (header->origin_m) data.cloud.origin_m = *header->origin_m;
    if (Expected<void> body = read_body(bytes, *header, source_name, data); !body) {
        return fail(body.error());
    }
    return data;
}

Expected<PlyData> read_ply(const std::filesystem::path& path) {
    const Expected<std::vector<char>> bytes = read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    return parse_ply(*bytes, path.string());
}

}  // namespace anascan::io
