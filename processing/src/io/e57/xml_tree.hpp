#pragma once
/// \file
/// The XML section of an E57 file as a small element tree, parsed with expat.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::io::e57 {

/// One XML element: its name, attributes, text (CDATA included) and children.
struct XmlNode {
    std::string name;
    std::vector<std::pair<std::string, std::string>> attributes;
    std::string text;
    std::vector<XmlNode> children;
    std::uint64_t xml_byte = 0;  ///< Offset of the start tag within the XML section.

    /// The first child called `child_name`, or nullptr.
    const XmlNode* child(std::string_view child_name) const;
    /// The value of attribute `key`, or nullptr.
    const std::string* attribute(std::string_view key) const;
    /// The E57 element type ("Structure", "Integer", ...): the `type` attribute.
    std::string_view type() const;
};

/// Where the XML section lies, so that errors name the file and the byte offset.
struct XmlSource {
    std::string_view source;            ///< File name.
    std::uint64_t physical_offset = 0;  ///< Physical offset of the section's first byte.

    /// "SOURCE: byte N: what", N the physical offset of XML byte `xml_byte`.
    Error error(ErrorCode code, std::uint64_t xml_byte, std::string_view what) const;
};

/// Limits that bound the tree's memory whatever the input says.
struct XmlLimits {
    int max_depth = 64;
    std::size_t max_elements = 500'000;
};

/// Parses the XML text into its root element.
Expected<XmlNode> parse_xml(std::span<const std::uint8_t> xml, const XmlSource& where,
                            const XmlLimits& limits = {});

}  // namespace anascan::io::e57
