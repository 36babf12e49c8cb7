#include "bytestreams.hpp"

#include <bit>
#include <string>

namespace anascan::io::e57 {
namespace {

enum PacketType : std::uint8_t { kIndexPacket = 0, kDataPacket = 1, kEmptyPacket = 2 };

/// The section and where its data packets start, in logical offsets.
struct Section {
    std::uint64_t begin = 0;  ///< Logical offset of the section header.
    std::uint64_t end = 0;    ///< One past the section's last logical byte.
    std::uint64_t data = 0;   ///< Logical offset of the first data packet.
};

std::uint64_t total_bits(const CompressedVectorSpec& cv) {
    std::uint64_t bits = 0;
    for (const FieldSpec& f : cv.fields) bits += std::uint64_t(f.bits);
    return bits;
}

Expected<Section> read_section(const PagedFile& file, const CompressedVectorSpec& cv,
                               std::string_view what) {
    const std::string name(what);
    auto header = file.read(cv.physical_offset, kSectionHeaderBytes, name + ": section header");
    if (!header) return fail(header.error());
    if ((*header)[0] != 1) {
        return fail(file.error_at(
            ErrorCode::kFormat, cv.physical_offset,
            name + ": not a compressed-vector section (id " + std::to_string((*header)[0]) + ")"));
    }
    const std::uint64_t length = load_u64(*header, 8);
    const std::uint64_t data_physical = load_u64(*header, 16);
    if (length < kSectionHeaderBytes) {
        return fail(file.error_at(
            ErrorCode::kFormat, cv.physical_offset + 8,
            name + ": section length " + std::to_string(length) + " is shorter than its header"));
    }
    if (auto all = file.read(cv.physical_offset, length, name + ": section"); !all) {
        return fail(all.error());
    }
    Section s{.begin = to_logical(cv.physical_offset)};
    s.end = s.begin + length;
    s.data = to_logical(data_physical);
    const bool data_inside = s.data >= s.begin + kSectionHeaderBytes && s.data <= s.end &&
                             data_physical % kPageBytes < kPageDataBytes;
    if (!data_inside && cv.record_count > 0) {
        return fail(file.error_at(
            ErrorCode::kFormat, cv.physical_offset + 16,
            name + ": data offset " + std::to_string(data_physical) + " lies outside its section"));
    }
    return s;
}

// Checks that `record_count` records fit in the section: bounds memory for lying counts.
Expected<void> check_record_count(const PagedFile& file, const CompressedVectorSpec& cv,
                                  const Section& s, std::string_view what) {
    const std::uint64_t bits = std::max<std::uint64_t>(total_bits(cv), 8);
    const std::uint64_t room = (s.end - s.begin) * 8 / bits;
    if (cv.record_count > room) {
        return fail(file.error_at(ErrorCode::kFormat, cv.physical_offset,
                                  std::string(what) + ": " + std::to_string(cv.record_count) +
                                      " records announced, but the section's " +
                                      std::to_string(s.end - s.begin) + " bytes hold at most " +
                                      std::to_string(room)));
    }
    return {};
}

// Appends one data packet's buffers to their streams, after checking its header.
Expected<void> append_packet(const PagedFile& file, std::span<const std::uint8_t> packet,
                             std::uint64_t physical, const std::string& name,
                             std::vector<std::vector<std::uint8_t>>& streams) {
    const std::size_t count = packet.size() >= kDataPacketHeaderBytes ? load_u16(packet, 4) : 0;
    if (count != streams.size()) {
        return fail(file.error_at(ErrorCode::kFormat, physical,
                                  name + ": data packet with " + std::to_string(count) +
                                      " bytestreams, the prototype has " +
                                      std::to_string(streams.size()) + " fields"));
    }
    std::size_t at = kDataPacketHeaderBytes + 2 * count;
    std::size_t total = 0;
    for (std::size_t i = 0; i < count && at <= packet.size(); ++i)
        total += load_u16(packet, kDataPacketHeaderBytes + 2 * i);
    if (at + total > packet.size()) {
        return fail(file.error_at(ErrorCode::kFormat, physical,
                                  name + ": bytestream buffers of " + std::to_string(total) +
                                      " bytes overrun their packet of " +
                                      std::to_string(packet.size()) + " bytes"));
    }
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t n = load_u16(packet, kDataPacketHeaderBytes + 2 * i);
        streams[i].insert(streams[i].end(), packet.begin() + at, packet.begin() + at + n);
        at += n;
    }
    return {};
}

// The error for a section that ends before field `i` holds all its records.
Error short_stream_error(const PagedFile& file, std::uint64_t physical, const std::string& name,
                         const CompressedVectorSpec& cv, std::size_t i, std::uint64_t have,
                         std::uint64_t needed) {
    return file.error_at(ErrorCode::kTruncated, physical,
                         name + ": the section ends with field '" + cv.fields[i].name + "' at " +
                             std::to_string(have) + " of " + std::to_string(needed) +
                             " bytes for " + std::to_string(cv.record_count) + " records");
}

}  // namespace

Expected<std::vector<std::vector<std::uint8_t>>> read_bytestreams(const PagedFile& file,
                                                                  const CompressedVectorSpec& cv,
                                                                  std::string_view what) {
    const std::string name(what);
    auto section = read_section(file, cv, what);
    if (!section) return fail(section.error());
    if (auto ok = check_record_count(file, cv, *section, what); !ok) return fail(ok.error());
    std::vector<std::vector<std::uint8_t>> streams(cv.fields.size());
    std::vector<std::uint64_t> needed(cv.fields.size());
    for (std::size_t i = 0; i < cv.fields.size(); ++i) {
        needed[i] = (cv.record_count * std::uint64_t(cv.fields[i].bits) + 7) / 8;
    }
    const auto short_stream = [&] {
        for (std::size_t i = 0; i < streams.size(); ++i)
            if (streams[i].size() < needed[i]) return i;
        return streams.size();
    };
    std::uint64_t at = section->data;
    for (std::size_t i = short_stream(); cv.record_count > 0 && i < streams.size();
         i = short_stream()) {
        const std::uint64_t physical = to_physical(at);
        if (section->end - at < 4) {
            return fail(
                short_stream_error(file, physical, name, cv, i, streams[i].size(), needed[i]));
        }
        auto head = file.read(physical, 4, name + ": packet header");
        if (!head) return fail(head.error());
        const std::uint8_t type = (*head)[0];
        const std::uint64_t length = std::uint64_t(load_u16(*head, 2)) + 1;
        if (length > section->end - at) {
            return fail(file.error_at(ErrorCode::kTruncated, physical,
                                      name + ": packet of " + std::to_string(length) +
                                          " bytes runs past the end of its section"));
        }
        if (type == kDataPacket) {
            auto packet = file.read(physical, length, name + ": data packet");
            if (!packet) return fail(packet.error());
            if (auto ok = append_packet(file, *packet, physical, name, streams); !ok)
                return fail(ok.error());
        } else if (type != kIndexPacket && type != kEmptyPacket) {
            return fail(file.error_at(ErrorCode::kFormat, physical,
                                      name + ": unknown packet type " + std::to_string(type)));
        }
        at += length;
    }
    return streams;
}

std::uint64_t BitReader::next(int bits) {
    if (bits == 0) return 0;
    const std::uint64_t byte = bit_ >> 3;
    const int shift = int(bit_ & 7);
    const int span_bytes = (shift + bits + 7) / 8;
    std::uint64_t v = 0;
    for (int i = 0; i < span_bytes && i < 8; ++i) v |= std::uint64_t(bytes_[byte + i]) << (8 * i);
    v >>= shift;
    if (span_bytes == 9) v |= std::uint64_t(bytes_[byte + 8]) << (64 - shift);
    bit_ += std::uint64_t(bits);
    return bits == 64 ? v : v & ((std::uint64_t(1) << bits) - 1);
}

std::int64_t next_integer(const FieldSpec& f, BitReader& reader) {
    return std::int64_t(std::uint64_t(f.minimum) + reader.next(f.bits));
}

double next_value(const FieldSpec& f, BitReader& reader) {
    switch (f.kind) {
        case FieldKind::kInteger:
            return double(next_integer(f, reader));
        case FieldKind::kScaledInteger:
            return double(next_integer(f, reader)) * f.scale + f.offset;
        case FieldKind::kFloat:
            if (f.single_precision)
                return double(std::bit_cast<float>(std::uint32_t(reader.next(32))));
            return std::bit_cast<double>(reader.next(64));
    }
    return 0.0;
}

}  // namespace anascan::io::e57
