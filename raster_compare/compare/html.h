// Text into HTML, for the report and the index page: the one escaping both use.
#pragma once

#include <cstdio>
#include <optional>
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

// Percent-encodes every byte but the unreserved characters of RFC 3986 and those in `keep` ("/"
// for a relative path): a link built from user text stays a relative link ("javascript:", '#',
// spaces and quotes are encoded).
inline std::string urlEncode(const std::string& s, const std::string& keep) {
    std::string o;
    for (unsigned char c : s) {
        const bool unreserved = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                                (c >= '0' && c <= '9') || c == '-' || c == '.' || c == '_' ||
                                c == '~';
        if (unreserved || keep.find(char(c)) != std::string::npos) {
            o += char(c);
        } else {
            char buf[4];
            std::snprintf(buf, sizeof buf, "%%%02X", c);
            o += buf;
        }
    }
    return o;
}

// The mark the reports put after a row's label when the design it grades is not its anchor's as
// published (issue 63): "variant" or "own", its provenance (sources and deviations) as the
// tooltip; nothing for a faithful row, an image or a file written before provenance.
inline std::string fidelityMark(const std::string& fidelity, const std::string& provenance) {
    if (fidelity != "variant" && fidelity != "own") return "";
    return " <sup class=\"fidelity\" data-fidelity=\"" + fidelity + "\" title=\"" +
           htmlEscape(provenance) + "\">" + fidelity + "</sup>";
}

// The note the reports put after the label of a row that builds over frames (metrics.json's
// history_frames, docs/metrics.md#history-frames): "cold start (no history)" where one frame was
// judged, else how many frames built it; nothing for the other rows.
inline std::string historyMark(const std::optional<int>& historyFrames) {
    if (!historyFrames) return "";
    const std::string text = *historyFrames == 0
                                 ? "cold start (no history)"
                                 : "history of " + std::to_string(*historyFrames) + " frames";
    return " <span class=\"history muted\" data-history-frames=\"" +
           std::to_string(*historyFrames) +
           "\" title=\"it builds over frames: judged after this many (compare --converge N, "
           "--sequence)\">" +
           text + "</span>";
}

}  // namespace so
