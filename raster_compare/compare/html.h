// Text into HTML, for the report and the index page: the one escaping both use.
#pragma once

#include <string>

namespace so {

// <, >, & and " as entities: safe in element text and in double-quoted attribute values.
inline std::string htmlEscape(const std::string& s) {
    std::string o;
    o.reserve(s.size());
    for (char c : s)
        o += c == '<'   ? "&lt;"
             : c == '>' ? "&gt;"
             : c == '&' ? "&amp;"
             : c == '"' ? "&quot;"
                        : std::string(1, c);
    return o;
}

}  // namespace so
