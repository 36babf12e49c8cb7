#include "xml_tree.hpp"

#include <expat.h>

#include <limits>
#include <memory>

#include "paged_file.hpp"

namespace anascan::io::e57 {
namespace {

/// What expat's callbacks build: a stack of open elements and the finished root.
struct Builder {
    XML_Parser parser = nullptr;
    XmlLimits limits;
    std::vector<XmlNode> open;
    XmlNode root;
    bool have_root = false;
    std::size_t elements = 0;
    std::string limit_error;

    std::uint64_t byte() const { return std::uint64_t(XML_GetCurrentByteIndex(parser)); }
    void stop(std::string what) {
        limit_error = std::move(what);
        XML_StopParser(parser, XML_FALSE);
    }
};

void XMLCALL on_start(void* user, const XML_Char* name, const XML_Char** attributes) {
    Builder& b = *static_cast<Builder*>(user);
    if (++b.elements > b.limits.max_elements) {
        return b.stop("more than " + std::to_string(b.limits.max_elements) + " XML elements");
    }
    if (int(b.open.size()) >= b.limits.max_depth) {
        return b.stop("XML nested deeper than " + std::to_string(b.limits.max_depth));
    }
    XmlNode node{.name = name, .xml_byte = b.byte()};
    for (const XML_Char** a = attributes; a[0] != nullptr; a += 2) {
        node.attributes.emplace_back(a[0], a[1]);
    }
    b.open.push_back(std::move(node));
}

void XMLCALL on_end(void* user, const XML_Char*) {
    Builder& b = *static_cast<Builder*>(user);
    XmlNode node = std::move(b.open.back());
    b.open.pop_back();
    if (b.open.empty()) {
        b.root = std::move(node);
        b.have_root = true;
    } else {
        b.open.back().children.push_back(std::move(node));
    }
}

void XMLCALL on_text(void* user, const XML_Char* text, int length) {
    Builder& b = *static_cast<Builder*>(user);
    if (!b.open.empty()) b.open.back().text.append(text, std::size_t(length));
}

// One RAII owner of the expat parser.
struct ParserDeleter {
    void operator()(XML_ParserStruct* p) const { XML_ParserFree(p); }
};

}  // namespace

Error XmlSource::error(ErrorCode code, std::uint64_t xml_byte, std::string_view what) const {
    const std::uint64_t physical = to_physical(to_logical(physical_offset) + xml_byte);
    return Error{code, std::string(source) + ": byte " + std::to_string(physical) + ": " +
                           std::string(what)};
}

const XmlNode* XmlNode::child(std::string_view child_name) const {
    for (const XmlNode& c : children)
        if (c.name == child_name) return &c;
    return nullptr;
}

const std::string* XmlNode::attribute(std::string_view key) const {
    for (const auto& [k, v] : attributes)
        if (k == key) return &v;
    return nullptr;
}

std::string_view XmlNode::type() const {
    const std::string* t = attribute("type");
    return t ? std::string_view(*t) : std::string_view();
}

Expected<XmlNode> parse_xml(std::span<const std::uint8_t> xml, const XmlSource& where,
                            const XmlLimits& limits) {
    if (xml.size() > std::size_t(std::numeric_limits<int>::max())) {
        return fail(where.error(ErrorCode::kUnsupported, 0, "XML section larger than 2 GiB"));
    }
    const std::unique_ptr<XML_ParserStruct, ParserDeleter> parser(XML_ParserCreate("UTF-8"));
    if (!parser) return fail(where.error(ErrorCode::kIo, 0, "cannot create an XML parser"));
    Builder b{.parser = parser.get(), .limits = limits};
    XML_SetUserData(parser.get(), &b);
    XML_SetElementHandler(parser.get(), on_start, on_end);
    XML_SetCharacterDataHandler(parser.get(), on_text);
    const auto status = XML_Parse(parser.get(), reinterpret_cast<const char*>(xml.data()),
                                  int(xml.size()), XML_TRUE);
    if (!b.limit_error.empty())
        return fail(where.error(ErrorCode::kFormat, b.byte(), b.limit_error));
    if (status != XML_STATUS_OK) {
        const XML_Error code = XML_GetErrorCode(parser.get());
        return fail(where.error(ErrorCode::kFormat, b.byte(),
                                std::string("XML section: ") + XML_ErrorString(code) + " (line " +
                                    std::to_string(XML_GetCurrentLineNumber(parser.get())) + ")"));
    }
    if (!b.have_root) return fail(where.error(ErrorCode::kFormat, 0, "XML section has no root"));
    return std::move(b.root);
}

}  // namespace anascan::io::e57
