#include "core/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/geometric.hpp>

namespace so {

const json& JsonReader::at(const json& obj, const std::string& field,
                           const std::string& key) const {
    requireObject(obj, field);
    const json* v = find(obj, key);
    if (!v) fail(join(field, printable(key, 40)), "missing");
    return *v;
}

const json* JsonReader::find(const json& obj, const std::string& key) {
    if (!obj.is_object()) return nullptr;
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
}

void JsonReader::requireObject(const json& j, const std::string& field) const {
    if (!j.is_object()) wrongType(j, field, "an object");
}

void JsonReader::requireArray(const json& j, const std::string& field) const {
    if (!j.is_array()) wrongType(j, field, "an array");
}

void JsonReader::requireArraySize(const json& j, const std::string& field, size_t min,
                                  size_t limit) const {
    requireArray(j, field);
    if (j.size() < min) fail(field, "needs at least " + std::to_string(min) + " entries");
    if (j.size() > limit)
        fail(field, std::to_string(j.size()) + " entries, limit is " + std::to_string(limit));
}

void JsonReader::checkKeys(const json& j, const std::string& field,
                           const std::vector<std::string>& allowed,
                           const std::string& context) const {
    requireObject(j, field);
    for (auto it = j.begin(); it != j.end(); ++it) checkKey(it.key(), field, allowed, context);
}

void JsonReader::checkKey(const std::string& key, const std::string& field,
                          const std::vector<std::string>& allowed,
                          const std::string& context) const {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) return;
    fail(join(field, printable(key, 40)),
         "unknown key" + context + " (valid: " + list(allowed) + ")");
}

double JsonReader::number(const json& j, const std::string& field) const {
    if (!j.is_number()) wrongType(j, field, "a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(field, "not a finite number");
    return v;
}

double JsonReader::numberAtLeast(const json& j, const std::string& field, double lo) const {
    const double v = number(j, field);
    if (v < lo) outOfRange(field, ">= " + numberText(lo), v);
    return v;
}

double JsonReader::numberIn(const json& j, const std::string& field, double lo, double hi) const {
    const double v = number(j, field);
    if (v < lo || v > hi)
        outOfRange(field, "in [" + numberText(lo) + ", " + numberText(hi) + "]", v);
    return v;
}

double JsonReader::nullableNumber(const json& j, const std::string& field) const {
    if (j.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!j.is_number()) wrongType(j, field, "a number or null");
    return j.get<double>();
}

std::vector<double> JsonReader::numbers(const json& j, const std::string& field) const {
    if (!j.is_array()) wrongType(j, field, "an array of numbers");
    std::vector<double> out;
    for (size_t i = 0; i < j.size(); ++i) out.push_back(number(j[i], index(field, i)));
    return out;
}

int JsonReader::integer(const json& j, const std::string& field, int lo, int hi) const {
    if (!j.is_number()) wrongType(j, field, "an integer");
    const double v = j.get<double>();
    if (!std::isfinite(v) || v != std::floor(v))
        fail(field, "expected an integer, got " + printable(j.dump(), 40));
    if (v < lo || v > hi)
        outOfRange(field, "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", v);
    return int(v);
}

uint64_t JsonReader::count(const json& j, const std::string& field) const {
    if (j.is_number_unsigned()) return j.get<uint64_t>();
    if (j.is_number_integer() && j.get<int64_t>() >= 0) return uint64_t(j.get<int64_t>());
    if (!j.is_number()) wrongType(j, field, "a non-negative integer");
    fail(field, "expected a non-negative integer, got " + printable(j.dump(), 40));
}

bool JsonReader::boolean(const json& j, const std::string& field) const {
    if (!j.is_boolean()) wrongType(j, field, "true or false");
    return j.get<bool>();
}

std::string JsonReader::string(const json& j, const std::string& field) const {
    if (!j.is_string()) wrongType(j, field, "a string");
    return j.get<std::string>();
}

std::vector<std::string> JsonReader::strings(const json& j, const std::string& field) const {
    if (!j.is_array()) wrongType(j, field, "an array of strings");
    std::vector<std::string> out;
    for (size_t i = 0; i < j.size(); ++i) out.push_back(string(j[i], index(field, i)));
    return out;
}

std::string JsonReader::oneOf(const json& j, const std::string& field, const std::string& what,
                              const std::vector<std::string>& names) const {
    if (!j.is_string()) wrongType(j, field, "a string");
    const std::string s = j.get<std::string>();
    if (std::find(names.begin(), names.end(), s) == names.end())
        fail(field,
             "unknown " + what + " \"" + printable(s, 40) + "\" (valid: " + list(names) + ")");
    return s;
}

glm::dvec3 JsonReader::vec3(const json& j, const std::string& field) const {
    if (!j.is_array() || j.size() != 3)
        fail(field, "expected an array of 3 numbers, got " +
                        (j.is_array() ? "an array of " + std::to_string(j.size()) : typeName(j)));
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i) v[i] = number(j[i], index(field, size_t(i)));
    return v;
}

glm::dvec3 JsonReader::unitVec3(const json& j, const std::string& field) const {
    const glm::dvec3 v = vec3(j, field);
    const double len = glm::length(v);
    if (!(len > 0.0) || !std::isfinite(len)) fail(field, "zero length");
    return v / len;
}

std::string JsonReader::typeName(const json& j) {
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

std::string JsonReader::list(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

std::string JsonReader::numberText(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

}  // namespace so
