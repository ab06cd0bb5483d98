// Typed, path-tracking access to a scene file's JSON (docs/scene-format.md), shared by the scene
// parser and the per-type light parsers (core/lights/): every error names the file and the field as
// the user wrote it ("lights[2].vertices[1]") in one line.
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace so {

using nlohmann::json;

// Typed, path-tracking access to a JSON value, so every error names the field as a user wrote it.
class JsonReader {
  public:
    explicit JsonReader(std::string file) : file_(std::move(file)) {}
    const std::string& file() const { return file_; }

    [[noreturn]] void fail(const std::string& field, const std::string& msg) const {
        throwInputError(file_, field, msg);
    }

    void requireObject(const json& j, const std::string& field) const {
        if (!j.is_object()) fail(field, "expected an object, got " + typeName(j));
    }

    void checkKeys(const json& j, const std::string& field,
                   std::initializer_list<const char*> allowed,
                   const std::string& context = "") const {
        checkKeys(j, field, std::vector<std::string>(allowed.begin(), allowed.end()), context);
    }

    // Fails on the first key of `j` not in `allowed`, naming the valid ones.
    void checkKeys(const json& j, const std::string& field, const std::vector<std::string>& allowed,
                   const std::string& context = "") const {
        for (auto it = j.begin(); it != j.end(); ++it) {
            if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
            std::string list;
            for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
            fail(join(field, it.key()), "unknown key" + context + " (valid: " + list + ")");
        }
    }

    double number(const json& j, const std::string& field) const {
        if (!j.is_number()) fail(field, "expected a number, got " + typeName(j));
        double v = j.get<double>();
        if (!std::isfinite(v)) fail(field, "not a finite number");
        return v;
    }

    int integer(const json& j, const std::string& field, int lo, int hi) const {
        if (!j.is_number_integer() && !(j.is_number_float() && isIntegral(j.get<double>())))
            fail(field, "expected an integer, got " + (j.is_number() ? dumpShort(j) : typeName(j)));
        double v = j.get<double>();
        if (v < lo || v > hi)
            fail(field, dumpShort(j) + " is out of range [" + std::to_string(lo) + ", " +
                            std::to_string(hi) + "]");
        return int(v);
    }

    std::string string(const json& j, const std::string& field) const {
        if (!j.is_string()) fail(field, "expected a string, got " + typeName(j));
        return j.get<std::string>();
    }

    glm::dvec3 vec3(const json& j, const std::string& field) const {
        if (!j.is_array() || j.size() != 3)
            fail(field,
                 "expected an array of 3 numbers, got " +
                     (j.is_array() ? "an array of " + std::to_string(j.size()) : typeName(j)));
        glm::dvec3 v;
        for (int i = 0; i < 3; ++i) v[i] = number(j[i], field + "[" + std::to_string(i) + "]");
        return v;
    }

    glm::dvec3 unitVec3(const json& j, const std::string& field) const {
        glm::dvec3 v = vec3(j, field);
        double len = glm::length(v);
        if (!(len > 0.0) || !std::isfinite(len)) fail(field, "zero length");
        return v / len;
    }

    static std::string join(const std::string& parent, const std::string& key) {
        return parent.empty() ? key : parent + "." + key;
    }
    static std::string index(const std::string& parent, size_t i) {
        return parent + "[" + std::to_string(i) + "]";
    }

    static std::string typeName(const json& j) {
        switch (j.type()) {
            case json::value_t::null:
                return "null";
            case json::value_t::object:
                return "an object";
            case json::value_t::array:
                return "an array";
            case json::value_t::string:
                return "a string";
            case json::value_t::boolean:
                return "a boolean";
            default:
                return "a number";
        }
    }

  private:
    static bool isIntegral(double v) { return std::isfinite(v) && v == std::floor(v); }
    static std::string dumpShort(const json& j) { return printable(j.dump(), 40); }
    std::string file_;
};

// A point or vector as the scene format writes it: [x, y, z].
inline json jsonVec3(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

}  // namespace so
