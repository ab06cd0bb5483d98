// Two tiers of errors, as in pbrt: InputError for anything a user can get wrong (a bad scene file,
// a bad option), reported as one line "FILE: FIELD: message" with exit code 2; and CHECK for broken
// invariants of our own code, which throws InternalError with both values in its message. Library
// code never ends the process (it is linked into a shared library and a Python module): a caller's
// misuse of an API is std::invalid_argument, and only the program's main decides how to exit.
#pragma once

#include <stdexcept>
#include <string>

namespace so {

// A user error. what() is the complete one-line message "file: field: message".
class InputError : public std::runtime_error {
  public:
    InputError(std::string file, std::string field, std::string message);
    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }
    const std::string& message() const { return message_; }

  private:
    std::string file_, field_, message_;
};

// A broken invariant of our own code (SO_CHECK). what() is one line:
// "internal error: FILE:LINE: CHECK(expr) failed [with a vs b]".
class InternalError : public std::logic_error {
  public:
    using std::logic_error::logic_error;
};

[[noreturn]] void throwInputError(const std::string& file, const std::string& field,
                                  const std::string& message);

// Makes a string safe to put on one line of an error message (control characters escaped, length
// capped) because field names and values may come from hostile files.
std::string printable(const std::string& s, size_t maxLen = 80);

// Throws InternalError. Never use SO_CHECK where an exception cannot pass: a destructor, a noexcept
// function, or a callback that a C library (Embree, GL) calls.
[[noreturn]] void checkFailed(const char* file, int line, const char* expr, const std::string& a,
                              const std::string& b);

}  // namespace so

#define SO_CHECK(cond)                                                     \
    do {                                                                   \
        if (!(cond)) ::so::checkFailed(__FILE__, __LINE__, #cond, "", ""); \
    } while (0)

#define SO_CHECK_OP(a, op, b)                                                               \
    do {                                                                                    \
        auto&& so_a_ = (a);                                                                 \
        auto&& so_b_ = (b);                                                                 \
        if (!(so_a_ op so_b_))                                                              \
            ::so::checkFailed(__FILE__, __LINE__, #a " " #op " " #b, std::to_string(so_a_), \
                              std::to_string(so_b_));                                       \
    } while (0)
#define SO_CHECK_EQ(a, b) SO_CHECK_OP(a, ==, b)
#define SO_CHECK_LT(a, b) SO_CHECK_OP(a, <, b)
#define SO_CHECK_LE(a, b) SO_CHECK_OP(a, <=, b)
