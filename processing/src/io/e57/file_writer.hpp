#pragma once
/// \file
/// Assembles an E57 file from prepared scans: header, one compressed-vector section per
/// scan, the XML section, and the checksummed pages. encode_e57 uses it for our clouds;
/// tests use it to build files with other field encodings and with deliberate faults.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "section_writer.hpp"

namespace anascan::io::e57 {

/// One data3D entry ready to be written.
struct ScanSection {
    std::string name;
    std::string guid;  ///< A new GUID when empty.
    std::optional<Pose> T_file_scan;
    std::string extra_xml;  ///< More children of the data3D entry (e.g. colorLimits).
    std::vector<FieldStream> fields;
    std::uint64_t record_count = 0;  ///< Records in the fields' bytestreams.
    /// The recordCount the XML announces when it differs (tests make it lie).
    std::optional<std::uint64_t> announced_count;
};

/// The whole file.
std::vector<char> assemble_file(std::span<const ScanSection> scans);

}  // namespace anascan::io::e57
