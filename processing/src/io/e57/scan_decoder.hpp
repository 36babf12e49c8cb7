#pragma once
/// \file
/// Turns one data3D entry's decoded records into a scan: coordinates, attributes, grid.

#include <string_view>

#include "anascan/processing/io/e57.hpp"
#include "paged_file.hpp"
#include "schema.hpp"

namespace anascan::io::e57 {

/// Decodes the points of `spec` (its bytestreams read from `file`) into an E57Scan.
/// `index` is the scan's place in data3D; the scan id is "<stem>#<index>".
Expected<E57Scan> decode_scan(const PagedFile& file, const ScanSpec& spec, std::size_t index);

}  // namespace anascan::io::e57
