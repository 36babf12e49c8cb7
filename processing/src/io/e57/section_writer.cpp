#include "section_writer.hpp"

#include <bit>
#include <string>

#include "bytestreams.hpp"
#include "io/text_lines.hpp"
#include "paged_file.hpp"

namespace anascan::io::e57 {
namespace {

/// Bits a data packet may carry, with room to spare under the 64 KiB packet limit.
constexpr std::uint64_t kPacketPayloadBits = 60000 * 8;

FieldStream float_field(std::string name, bool single) {
    return {.spec = {.name = std::move(name),
                     .kind = FieldKind::kFloat,
                     .single_precision = single,
                     .bits = single ? 32 : 64}};
}

FieldStream integer_field(std::string name, std::int64_t maximum) {
    return {.spec = {.name = std::move(name),
                     .kind = FieldKind::kInteger,
                     .minimum = 0,
                     .maximum = maximum,
                     .bits = bits_for_range(0, maximum)}};
}

// The grid cell of every point; kInvalidArgument unless each point has exactly one cell.
Expected<std::vector<std::int64_t>> cells_of_points(const E57Scan& scan) {
    const RangeGrid& grid = scan.grid;
    const std::size_t n = scan.scan.cloud.size();
    if (grid.point_index.size() != std::size_t(grid.rows) * std::size_t(grid.cols)) {
        return fail(ErrorCode::kInvalidArgument,
                    "E57 writer: scan '" + scan.name + "': grid size differs from rows x cols");
    }
    std::vector<std::int64_t> cell(n, -1);
    for (std::size_t c = 0; c < grid.point_index.size(); ++c) {
        const std::int32_t i = grid.point_index[c];
        if (i == RangeGrid::kNoSample) continue;
        if (i < 0 || std::size_t(i) >= n || cell[std::size_t(i)] >= 0) {
            return fail(ErrorCode::kInvalidArgument, "E57 writer: scan '" + scan.name +
                                                         "': grid cell " + std::to_string(c) +
                                                         " names a missing or repeated point");
        }
        cell[std::size_t(i)] = std::int64_t(c);
    }
    if (std::ranges::find(cell, -1) != cell.end()) {
        return fail(ErrorCode::kInvalidArgument,
                    "E57 writer: scan '" + scan.name + "': a point has no grid cell");
    }
    return cell;
}

void add_grid_fields(const E57Scan& scan, const std::vector<std::int64_t>& cells,
                     std::vector<FieldStream>& out) {
    out.push_back(integer_field("rowIndex", scan.grid.rows - 1));
    out.push_back(integer_field("columnIndex", scan.grid.cols - 1));
    BitPacker rows(out[out.size() - 2]), cols(out.back());
    for (const std::int64_t c : cells) {
        rows.put(std::uint64_t(c / scan.grid.cols));
        cols.put(std::uint64_t(c % scan.grid.cols));
    }
}

// Appends one data packet carrying records [first, last) of every field.
void append_packet(std::vector<std::uint8_t>& logical, const std::vector<FieldStream>& fields,
                   std::uint64_t first, std::uint64_t last, bool final_packet) {
    const std::size_t packet = logical.size();
    logical.resize(packet + kDataPacketHeaderBytes + 2 * fields.size(), 0);
    logical[packet] = 1;  // data packet
    logical[packet + 4] = std::uint8_t(fields.size());
    logical[packet + 5] = std::uint8_t(fields.size() >> 8);
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::uint64_t bits = std::uint64_t(fields[i].spec.bits);
        const std::size_t size = fields[i].bytes.size();
        const std::size_t from = std::min(size, std::size_t((first * bits + 7) / 8));
        const std::size_t to =
            final_packet ? size : std::min(size, std::size_t((last * bits + 7) / 8));
        const std::size_t at = packet + kDataPacketHeaderBytes + 2 * i;
        logical[at] = std::uint8_t(to - from);
        logical[at + 1] = std::uint8_t((to - from) >> 8);
        logical.insert(logical.end(), fields[i].bytes.begin() + std::ptrdiff_t(from),
                       fields[i].bytes.begin() + std::ptrdiff_t(to));
    }
    logical.resize((logical.size() + 3) / 4 * 4, 0);
    const std::size_t length_minus_1 = logical.size() - packet - 1;
    logical[packet + 2] = std::uint8_t(length_minus_1);
    logical[packet + 3] = std::uint8_t(length_minus_1 >> 8);
}

}  // namespace

void BitPacker::put(std::uint64_t value) {
    const int bits = field_.spec.bits;
    for (int i = 0; i < bits; ++i, ++bit_) {
        if (bit_ % 8 == 0) field_.bytes.push_back(0);
        if ((value >> i) & 1u) field_.bytes.back() |= std::uint8_t(1u << (bit_ % 8));
    }
}

std::string prototype_xml(const std::vector<FieldStream>& fields) {
    std::string out = "<prototype type=\"Structure\">";
    for (const FieldStream& f : fields) {
        const FieldSpec& s = f.spec;
        out += "<" + s.name;
        if (s.kind == FieldKind::kFloat) {
            out += std::string(" type=\"Float\" precision=\"") +
                   (s.single_precision ? "single" : "double") + "\"/>";
            continue;
        }
        out += std::string(" type=\"") +
               (s.kind == FieldKind::kInteger ? "Integer" : "ScaledInteger") + "\" minimum=\"" +
               std::to_string(s.minimum) + "\" maximum=\"" + std::to_string(s.maximum) + "\"";
        if (s.kind == FieldKind::kScaledInteger)
            out += " scale=\"" + text::format_exact(s.scale) + "\" offset=\"" +
                   text::format_exact(s.offset) + "\"";
        out += "/>";
    }
    return out + "</prototype>";
}

Expected<std::vector<FieldStream>> encode_fields(const E57Scan& scan) {
    const PointCloud& cloud = scan.scan.cloud;
    if (!cloud.attributes_consistent()) {
        return fail(ErrorCode::kInvalidArgument,
                    "E57 writer: scan '" + scan.name + "': " + describe_inconsistency(cloud));
    }
    std::vector<FieldStream> out;
    for (int axis = 0; axis < 3; ++axis) {
        out.push_back(float_field(std::string("cartesian") + char('X' + axis), false));
        BitPacker bits(out.back());
        for (std::size_t i = 0; i < cloud.size(); ++i)
            bits.put(std::bit_cast<std::uint64_t>(cloud.world_position(i)[axis]));
    }
    if (cloud.has_intensity()) {
        out.push_back(float_field("intensity", true));
        BitPacker bits(out.back());
        for (const float v : cloud.intensity) bits.put(std::bit_cast<std::uint32_t>(v));
    }
    if (cloud.has_colors()) {
        for (const char* name : {"colorRed", "colorGreen", "colorBlue"})
            out.push_back(integer_field(name, 255));
        BitPacker r(out[out.size() - 3]), g(out[out.size() - 2]), b(out.back());
        for (const Rgb8& c : cloud.colors) r.put(c.r), g.put(c.g), b.put(c.b);
    }
    if (scan.grid.rows > 0 && scan.grid.cols > 0) {
        auto cells = cells_of_points(scan);
        if (!cells) return fail(cells.error());
        add_grid_fields(scan, *cells, out);
    }
    return out;
}

std::uint64_t append_section(std::vector<std::uint8_t>& logical,
                             const std::vector<FieldStream>& fields, std::uint64_t record_count) {
    const std::size_t begin = logical.size();
    logical.resize(begin + kSectionHeaderBytes, 0);
    std::uint64_t record_bits = 1;
    for (const FieldStream& f : fields) record_bits += std::uint64_t(f.spec.bits);
    const std::uint64_t per_packet = std::max<std::uint64_t>(1, kPacketPayloadBits / record_bits);
    for (std::uint64_t first = 0; first < record_count; first += per_packet) {
        const std::uint64_t last = std::min(record_count, first + per_packet);
        append_packet(logical, fields, first, last, last == record_count);
    }
    const auto put_u64 = [&](std::size_t at, std::uint64_t v) {
        for (int i = 0; i < 8; ++i) logical[at + i] = std::uint8_t(v >> (8 * i));
    };
    logical[begin] = 1;  // compressed-vector section
    put_u64(begin + 8, logical.size() - begin);
    put_u64(begin + 16, to_physical(begin + kSectionHeaderBytes));
    return to_physical(begin);
}

}  // namespace anascan::io::e57
