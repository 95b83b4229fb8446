#pragma once
// Escaping text for SVG and HTML documents.

#include <string>

namespace countershade {

// Replaces &, <, >, " and ' by their entities, so the text is safe in element content and in
// quoted attribute values.
std::string xml_escape(const std::string& text);

}  // namespace countershade
