// Text made safe for HTML and XML (SVG) element content and attribute values.
#pragma once
#include <string>

namespace bmfr {

/// &, <, >, " and ' as entities.
std::string escapeHtml(const std::string& text);

} // namespace bmfr
