#include "core/error.h"

#include <cstdio>

namespace so {

InputError::InputError(std::string file, std::string field, std::string message)
    : std::runtime_error(file + ": " + (field.empty() ? "" : field + ": ") + message),
      file_(std::move(file)),
      field_(std::move(field)),
      message_(std::move(message)) {}

void throwInputError(const std::string& file, const std::string& field,
                     const std::string& message) {
    throw InputError(file, field, message);
}

std::string printable(const std::string& s, size_t maxLen) {
    std::string out;
    for (unsigned char c : s) {
        if (out.size() >= maxLen) {
            out += "...";
            break;
        }
        if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

void checkFailed(const char* file, int line, const char* expr, const std::string& a,
                 const std::string& b) {
    std::string what = "internal error: " + std::string(file) + ":" + std::to_string(line) +
                       ": CHECK(" + expr + ") failed";
    // The values may be strings from a file (a channel name): kept to one line.
    if (!a.empty() || !b.empty()) what += " with " + printable(a) + " vs " + printable(b);
    throw InternalError(what);
}

}  // namespace so
