// The one reader of user JSON (core/json_reader.h): each mistake in its one wording, one line
// naming the file and the field (docs/scene-format.md#one-wording).
#include "core/json_reader.h"

#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

namespace so {
namespace {

// The InputError's whole text for `read`, or "" when it reads.
std::string error(const std::function<void(const JsonReader&)>& read) {
    try {
        read(JsonReader("f.json"));
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "f.json");
        return e.what();
    }
    return "";
}

TEST(JsonReader, EachMistakeHasOneWording) {
    const json j = json::parse(R"({"n": 1.5, "s": "x", "a": [1, 2], "b": true, "o": {"k": 1}})");
    EXPECT_EQ(error([&](auto& r) { r.number(j["s"], "s"); }),
              "f.json: s: expected a number, got a string");
    EXPECT_EQ(error([&](auto& r) { r.string(j["n"], "n"); }),
              "f.json: n: expected a string, got a number");
    EXPECT_EQ(error([&](auto& r) { r.boolean(j["o"], "o"); }),
              "f.json: o: expected true or false, got an object");
    EXPECT_EQ(error([&](auto& r) { r.requireObject(j["a"], "a"); }),
              "f.json: a: expected an object, got an array");
    EXPECT_EQ(error([&](auto& r) { r.requireArray(j["b"], "b"); }),
              "f.json: b: expected an array, got a boolean");
    EXPECT_EQ(error([&](auto& r) { r.vec3(j["a"], "a"); }),
              "f.json: a: expected an array of 3 numbers, got an array of 2");
    EXPECT_EQ(error([&](auto& r) { r.integer(j["n"], "n", 0, 9); }),
              "f.json: n: expected an integer, got 1.5");
    EXPECT_EQ(error([&](auto& r) { r.integer(j["a"][1], "a[1]", 3, 9); }),
              "f.json: a[1]: must be in [3, 9], got 2");
    EXPECT_EQ(error([&](auto& r) { r.numberIn(j["n"], "n", 2, 3); }),
              "f.json: n: must be in [2, 3], got 1.5");
    EXPECT_EQ(error([&](auto& r) { r.numberAtLeast(json(-1), "n", 0); }),
              "f.json: n: must be >= 0, got -1");
    EXPECT_EQ(error([&](auto& r) { r.number(json(NAN), "n"); }), "f.json: n: not a finite number");
    EXPECT_EQ(error([&](auto& r) { r.count(json(-3), "c"); }),
              "f.json: c: expected a non-negative integer, got -3");
    EXPECT_EQ(error([&](auto& r) { r.at(j["o"], "o", "m"); }), "f.json: o.m: missing");
    EXPECT_EQ(error([&](auto& r) {
                  r.checkKeys(j, "", {"n", "s", "a", "b"});
              }),
              "f.json: o: unknown key (valid: n, s, a, b)");
    EXPECT_EQ(error([&](auto& r) {
                  r.oneOf(j["s"], "s", "encoding", {"linear", "srgb"});
              }),
              "f.json: s: unknown encoding \"x\" (valid: linear, srgb)");
    EXPECT_EQ(error([&](auto& r) {
                  r.numbers(json::array({1, "2"}), "l");
              }),
              "f.json: l[1]: expected a number, got a string");
}

TEST(JsonReader, ReadsWhatIsRight) {
    const JsonReader r("f.json");
    EXPECT_EQ(r.integer(json(3.0), "i", 0, 9), 3);
    EXPECT_EQ(r.count(json(uint64_t(1) << 63), "c"), uint64_t(1) << 63);
    EXPECT_TRUE(std::isnan(r.nullableNumber(json(), "n")));
    EXPECT_EQ(r.nullableNumber(json(2.5), "n"), 2.5);
    EXPECT_EQ(r.oneOf(json("srgb"), "e", "encoding", {"linear", "srgb"}), "srgb");
    EXPECT_EQ(JsonReader::find(json::object(), "k"), nullptr);
    EXPECT_EQ(JsonReader::find(json::array(), "k"), nullptr);
}

// Field names come from the file: a hostile key stays on one line.
TEST(JsonReader, AHostileKeyStaysOnOneLine) {
    const json j = {{"bad\nkey", 1}};
    const std::string e = error([&](auto& r) { r.checkKeys(j, "", {"good"}); });
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    EXPECT_NE(e.find("unknown key (valid: good)"), std::string::npos) << e;
}

}  // namespace
}  // namespace so
