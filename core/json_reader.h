// The one reader of a user's JSON (scene files, sweep specs, limits and baselines, metrics.json,
// oracle.json, an image's sidecar): typed, path-tracking access whose every error is one line
// naming the file and the field as the user wrote it ("lights[2].vertices[1]"), in one wording
// per mistake (docs/scene-format.md#errors):
//
//   wrong type         expected a number, got a string
//   not an integer     expected an integer, got 1.5
//   missing            missing
//   unknown key        unknown key (valid: a, b)
//   unknown name       unknown <what> "x" (valid: a, b)
//   out of range       must be in [lo, hi], got 7        (or: must be >= 0, got -1)
//   not finite         not a finite number
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace so {

using nlohmann::json;

// Typed access to JSON values, so every error names the field as a user wrote it. Each getter
// takes the value and its field path (join, index build them) and throws InputError.
class JsonReader {
  public:
    explicit JsonReader(std::string file) : file_(std::move(file)) {}
    const std::string& file() const { return file_; }

    [[noreturn]] void fail(const std::string& field, const std::string& msg) const {
        throwInputError(file_, field, msg);
    }

    // The one wording of a number out of its range: "must be " + range + ", got " + value, with
    // range "in [lo, hi]", "in (0, 180)", ">= 0" or "> 0".
    [[noreturn]] void outOfRange(const std::string& field, const std::string& range,
                                 double value) const {
        fail(field, "must be " + range + ", got " + numberText(value));
    }

    // The member `key` of the object `obj` (at `field`), which must be there: "missing".
    const json& at(const json& obj, const std::string& field, const std::string& key) const;
    // The member, or nullptr where `obj` has none.
    static const json* find(const json& obj, const std::string& key);

    void requireObject(const json& j, const std::string& field) const;
    void requireArray(const json& j, const std::string& field) const;
    // An array of `min` to `limit` entries ("needs at least 2 entries", "20001 entries, limit is
    // 10000"): a keyframe list.
    void requireArraySize(const json& j, const std::string& field, size_t min, size_t limit) const;

    void checkKeys(const json& j, const std::string& field,
                   std::initializer_list<const char*> allowed,
                   const std::string& context = "") const {
        checkKeys(j, field, std::vector<std::string>(allowed.begin(), allowed.end()), context);
    }
    // Fails on the first key of `j` not in `allowed`, naming the valid ones; `context` says
    // whose keys they are (" for a point light").
    void checkKeys(const json& j, const std::string& field, const std::vector<std::string>& allowed,
                   const std::string& context = "") const;
    // One key of an object at `field`: for callers holding another JSON flavour (ordered_json),
    // which iterate their keys in the file's order themselves.
    void checkKey(const std::string& key, const std::string& field,
                  const std::vector<std::string>& allowed, const std::string& context = "") const;

    // A finite number.
    double number(const json& j, const std::string& field) const;
    double numberAtLeast(const json& j, const std::string& field, double lo) const;
    double numberIn(const json& j, const std::string& field, double lo, double hi) const;
    // A number, or null read as NaN: how oracle.json writes a non-finite value.
    double nullableNumber(const json& j, const std::string& field) const;
    std::vector<double> numbers(const json& j, const std::string& field) const;
    // An integer (1.0 counts) in [lo, hi].
    int integer(const json& j, const std::string& field, int lo, int hi) const;
    // A non-negative 64-bit integer: a counter.
    uint64_t count(const json& j, const std::string& field) const;
    bool boolean(const json& j, const std::string& field) const;
    std::string string(const json& j, const std::string& field) const;
    std::vector<std::string> strings(const json& j, const std::string& field) const;
    // One of `names`; `what` names the kind ("metric") in the error.
    std::string oneOf(const json& j, const std::string& field, const std::string& what,
                      const std::vector<std::string>& names) const;
    glm::dvec3 vec3(const json& j, const std::string& field) const;
    glm::dvec3 unitVec3(const json& j, const std::string& field) const;

    static std::string join(const std::string& parent, const std::string& key) {
        return parent.empty() ? key : parent + "." + key;
    }
    static std::string index(const std::string& parent, size_t i) {
        return parent + "[" + std::to_string(i) + "]";
    }
    // "a string", "an object", "null": what a wrong value was, for "expected X, got Y".
    static std::string typeName(const json& j);
    // "a, b, c", for "(valid: ...)".
    static std::string list(const std::vector<std::string>& names);
    // A number as the error quotes it ("got 7").
    static std::string numberText(double v);

  private:
    [[noreturn]] void wrongType(const json& j, const std::string& field,
                                const std::string& expected) const {
        fail(field, "expected " + expected + ", got " + typeName(j));
    }
    std::string file_;
};

// A point or vector as the scene format writes it: [x, y, z].
inline json jsonVec3(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

}  // namespace so
