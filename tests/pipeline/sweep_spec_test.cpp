// The sweep spec (docs/sweep.md): grids expanded in a stated order with exact range ends, task ids
// that do not move when the spec grows, and every mistake a one-line error naming its field.
// Label "loader": the ASan build runs it too.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/compare_option_table.h"
#include "core/error.h"
#include "core/raster_option_table.h"
#include "raster_compare/pipeline/sweep_spec.h"

namespace so {
namespace {

namespace fs = std::filesystem;

// A made-up technique table: "shadow" with alpha and min in [0, 16], an integer resolution, and
// a method parameter "filter" (box or tent, 0 or 1).
ParamNumbers validate(const std::string& technique, const std::vector<std::string>& settings) {
    if (technique != "shadow" && technique != "other")
        throwInputError("technique", technique, "unknown technique");
    ParamNumbers numbers;
    for (const std::string& kv : settings) {
        const std::string key = kv.substr(0, kv.find('=')), text = kv.substr(kv.find('=') + 1);
        if (key == "filter") {
            if (text != "box" && text != "tent" && text != "0" && text != "1")
                throwInputError(technique, key, "\"" + text + "\" is not box or tent");
            numbers[key] = text == "tent" || text == "1";
            continue;
        }
        const double v = std::stod(text);
        if (key != "alpha" && key != "min" && key != "resolution")
            throwInputError(technique, key, "unknown parameter");
        if (v < 0 || v > (key == "resolution" ? 8192 : 16))
            throwInputError(technique, key, key + " out of range");
        numbers[key] = v;
    }
    return numbers;
}

class SweepSpec : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("so_sweep_spec_" + std::to_string(::getpid()));
        fs::create_directories(dir_ / "scenes");
        for (const char* s : {"b.scene.json", "a.scene.json", "c.gltf"})
            std::ofstream(dir_ / "scenes" / s) << "{}";
    }
    void TearDown() override { fs::remove_all(dir_); }
    SweepPlan plan(const std::string& techniques,
                   const std::string& scenes = R"(["scenes/*.scene.json"])",
                   const std::string& extra = "") {
        const std::string text = R"({"sweep_format": 1, "scenes": )" + scenes + extra +
                                 R"(, "techniques": )" + techniques + "}";
        return planSweepText(text, dir_ / "spec.json", validate);
    }
    // The error's text, or "" when the spec was accepted.
    std::string error(const std::string& text) {
        try {
            planSweepText(text, dir_ / "spec.json", validate);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }
    fs::path dir_;
};

TEST_F(SweepSpec, GridsExpandWithTheLastParameterFastestAndExactRangeEnds) {
    const SweepPlan p = plan(R"([{"name": "shadow", "params": {
        "alpha": {"from": 0.1, "to": 0.7, "steps": 4}, "min": [0, 0.5], "resolution": 1024}}])");
    ASSERT_EQ(p.scenes.size(), 2u);
    EXPECT_EQ(p.scenes[0].name, "scenes/a.scene.json") << "globs are sorted";
    EXPECT_EQ(p.scenes[1].name, "scenes/b.scene.json");
    ASSERT_EQ(p.tasks.size(), 16u);
    EXPECT_EQ(p.tasks[0].label, "shadow:alpha=0.1,min=0,resolution=1024");
    EXPECT_EQ(p.tasks[1].label, "shadow:alpha=0.1,min=0.5,resolution=1024");
    EXPECT_EQ(p.tasks[2].label, "shadow:alpha=0.3,min=0,resolution=1024")
        << "not 0.30000000000000004";
    EXPECT_EQ(p.tasks[7].label, "shadow:alpha=0.7,min=0.5,resolution=1024");
    EXPECT_EQ(p.tasks[8].scene, 1u);
    ASSERT_EQ(p.tasks[7].swept.size(), 2u) << "resolution has one value: not swept";
    EXPECT_EQ(p.tasks[7].swept[0], (std::pair<std::string, double>{"alpha", 0.7}));
    EXPECT_EQ(p.tasks[7].swept[1], (std::pair<std::string, double>{"min", 0.5}));
    const SweepPlan log = plan(R"([{"name": "shadow", "params": {
        "resolution": {"from": 512, "to": 4096, "steps": 4, "log": true}}}])");
    std::vector<std::string> labels;
    for (size_t i = 0; i < 4; ++i) labels.push_back(log.tasks[i].label);
    // Log steps land on round numbers; whole numbers print as such; one step is `from`; a range
    // whose steps overflow is refused.
    const SweepPlan decades = plan(R"([{"name": "shadow", "params": {
        "alpha": {"from": 3, "to": 9, "steps": 1},
        "min": {"from": 0.0001, "to": 10, "steps": 6, "log": true}}}])");
    EXPECT_EQ(decades.tasks[3].label, "shadow:alpha=3,min=0.1");
    EXPECT_EQ(decades.tasks[4].label, "shadow:alpha=3,min=1");
    EXPECT_NE(error(R"({"sweep_format": 1, "scenes": ["scenes/a.scene.json"], "techniques": [
        {"name": "shadow", "params": {"alpha": {"from": -1e308, "to": 1e308, "steps": 3}}}]})")
                  .find("alpha out of range"),
              std::string::npos);
    EXPECT_EQ(labels,
              (std::vector<std::string>{"shadow:resolution=512", "shadow:resolution=1024",
                                        "shadow:resolution=2048", "shadow:resolution=4096"}));
}

// A parameter that picks a method takes its names (docs/sweep.md), as compare's --technique does:
// the labels keep the names, the swept values are the methods' numbers, as metrics.json's
// parameters hold them.
TEST_F(SweepSpec, MethodsAreSweptByName) {
    const SweepPlan p = plan(R"([{"name": "shadow", "params": {"filter": ["box", "tent"],
        "alpha": [1, 2]}}, {"name": "other", "params": {"filter": "tent"}}])",
                             R"(["scenes/a.scene.json"])");
    ASSERT_EQ(p.tasks.size(), 5u);
    EXPECT_EQ(p.tasks[0].label, "shadow:filter=box,alpha=1");
    EXPECT_EQ(p.tasks[3].label, "shadow:filter=tent,alpha=2");
    EXPECT_EQ(p.tasks[3].swept,
              (std::vector<std::pair<std::string, double>>{{"filter", 1.0}, {"alpha", 2.0}}));
    EXPECT_EQ(p.tasks[4].label, "other:filter=tent");
    EXPECT_TRUE(p.tasks[4].swept.empty());
}

TEST_F(SweepSpec, TaskIdsAreStableWhenTheSpecGrows) {
    const SweepPlan small = plan(R"([{"name": "shadow", "params": {"alpha": [1, 2]}}])");
    const SweepPlan grown =
        plan(R"([{"name": "other"}, {"name": "shadow", "params": {"alpha": [0, 1, 2]}}])",
             R"(["scenes/b.scene.json", "scenes/*.scene.json"])");
    std::map<std::string, std::string> idOf;  // scene + label -> id
    std::set<std::string> ids;
    for (const SweepTask& t : grown.tasks) {
        idOf[grown.scenes[t.scene].name + " " + t.label] = t.id;
        ids.insert(t.id);
        EXPECT_EQ(t.id.size(), 12u);
    }
    EXPECT_EQ(ids.size(), grown.tasks.size());
    EXPECT_EQ(grown.scenes.size(), 2u) << "a scene two entries match runs once";
    for (const SweepTask& t : small.tasks)
        EXPECT_EQ(idOf.at(small.scenes[t.scene].name + " " + t.label), t.id) << t.label;
    // A scene outside the spec's folder keeps a relative name (ids must not depend on where the
    // checkout lies); an absolute entry stays absolute.
    fs::create_directories(dir_ / "sweeps");
    const SweepPlan up =
        planSweepText(R"({"sweep_format": 1, "scenes": ["../scenes/a.scene.json", ")" +
                          (dir_ / "scenes" / "b.scene.json").string() +
                          R"("], "techniques": [{"name": "other"}]})",
                      dir_ / "sweeps" / "spec.json", validate);
    ASSERT_EQ(up.scenes.size(), 2u);
    EXPECT_EQ(up.scenes[0].name, "../scenes/a.scene.json");
    EXPECT_EQ(up.scenes[1].name, (dir_ / "scenes" / "b.scene.json").string());
    EXPECT_EQ(up.scenes[1].path, fs::weakly_canonical(dir_ / "scenes" / "b.scene.json"));
}

TEST_F(SweepSpec, MistakesNameTheFileAndTheField) {
    const std::string file = (dir_ / "spec.json").string();
    const std::string scenes = R"(, "scenes": ["scenes/a.scene.json"])";
    const auto spec = [&](const std::string& body) {
        return "{\"sweep_format\": 1" + scenes + body + "}";
    };
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"scenes": []})", "sweep_format: missing"},
        {R"({"sweep_format": 2})", "sweep_format: unsupported"},
        {spec(R"(, "techniques": [{"name": "shadow"}], "widht": 3)"), ": widht: unknown key"},
        {spec(R"(, "techniques": [{"name": "shadow"}], "oracle": {"sed": 1})"),
         "oracle.sed: unknown key"},
        {spec(R"(, "techniques": [{"name": "shadow"}], "oracle": {"target_error": 2})"),
         "oracle.target_error: must be in [0.0001, 0.5], got 2"},
        {spec(R"(, "techniques": [{"name": "nope"}])"), "techniques[0].name: unknown technique"},
        {spec(R"(, "techniques": [{"name": "shadow", "params": {"alpha": [1, "x"]}}])"),
         "techniques[0].params.alpha[1]: expected a number, got a string"},
        {spec(R"(, "techniques": [{"name": "shadow", "params": {"alpha": {"from": 0, "to": 1}}}])"),
         "techniques[0].params.alpha.steps: missing"},
        {spec(R"(, "techniques": [{"name": "shadow", "params": {"alpha": [1, 99]}}])"),
         "techniques[0].params: shadow:alpha=99: alpha out of range"},
        {spec(R"(, "techniques": [{"name": "shadow", "params": {"filter": ["box", "cubic"]}}])"),
         "techniques[0].params: shadow:filter=cubic: \"cubic\" is not box or tent"},
        {spec(R"(, "techniques": [{"name": "shadow", "params": {"filter": ["box", 1]}}])"),
         "techniques[0].params.filter[1]: a list of names holds names only"},
        {spec(R"(, "techniques": [{"name": "shadow", "params": {"filter": ["Box=1"]}}])"),
         "techniques[0].params.filter[0]: a method's name is 1 to 64 of a-z 0-9 _ -"},
        {spec(R"(, "techniques": [{"name": "shadow", "params": {"alpha": [1, 1]}}])"),
         "techniques: the setting shadow:alpha=1 is listed twice"},
        {spec(R"(, "techniques": [{"name": "shadow", "params": {
            "alpha": {"from": 0, "to": 1, "steps": 1000}, "min": {"from": 0, "to": 1, "steps": 101}}}])"),
         "the sweep has more than 100000 settings"},
        {spec(R"(, "techniques": [])"), "techniques: must be a non-empty list"},
        {R"({"sweep_format": 1, "scenes": ["scenes/*.glb"], "techniques": [{"name": "shadow"}]})",
         "scenes[0]: matches no scene file: scenes/*.glb"},
        {R"({"sweep_format": 1, "scenes": ["nope.json"], "techniques": [{"name": "shadow"}]})",
         "scenes[0]: no such scene file"},
        {"{\"sweep_format\": 1,", "invalid JSON: "},
    };
    for (const auto& [text, expected] : cases) {
        const std::string e = error(text);
        EXPECT_EQ(e.rfind(file + ": ", 0), 0u) << text << "\n -> " << e;
        EXPECT_NE(e.find(expected), std::string::npos) << text << "\n -> " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
    }
}

// A renderer's images (docs/sweep.md, "images"): per scene after that scene's technique settings,
// {scene} and {PARAM} filled in, the paths absolute, and every image present before anything runs.
class SweepSpecImages : public SweepSpec {
  protected:
    void SetUp() override {
        SweepSpec::SetUp();
        for (const char* scene : {"a", "b"})
            for (const char* bias : {"0.5", "1"}) {
                fs::create_directories(dir_ / "renders" / scene);
                std::ofstream(dir_ / "renders" / scene / (std::string("bias_") + bias + ".exr"))
                    << scene << bias;
            }
    }
    static std::string spec(const std::string& images, const std::string& techniques = "") {
        return R"({"sweep_format": 1, "scenes": ["scenes/*.scene.json"])" +
               (techniques.empty() ? "" : R"(, "techniques": )" + techniques) + R"(, "images": )" +
               images + "}";
    }
};

TEST_F(SweepSpecImages, FollowTheirScenesTechniquesWithPathsFilledIn) {
    const SweepPlan p =
        planSweepText(spec(R"([{"name": "engine", "path": "renders/{scene}/bias_{bias}.exr",
                  "params": {"bias": [0.5, 1], "cascades": 4}}])",
                           R"([{"name": "shadow", "params": {"alpha": [1, 2]}}])"),
                      dir_ / "spec.json", validate);
    ASSERT_EQ(p.tasks.size(), 8u);
    std::vector<std::string> labels;
    for (const SweepTask& t : p.tasks)
        labels.push_back(
            p.scenes[t.scene].name + " " + t.label + " " +
            (t.image.empty() ? "-" : fs::path(t.image).lexically_relative(dir_).string()));
    EXPECT_EQ(labels,
              (std::vector<std::string>{
                  "scenes/a.scene.json shadow:alpha=1 -", "scenes/a.scene.json shadow:alpha=2 -",
                  "scenes/a.scene.json engine:bias=0.5,cascades=4 renders/a/bias_0.5.exr",
                  "scenes/a.scene.json engine:bias=1,cascades=4 renders/a/bias_1.exr",
                  "scenes/b.scene.json shadow:alpha=1 -", "scenes/b.scene.json shadow:alpha=2 -",
                  "scenes/b.scene.json engine:bias=0.5,cascades=4 renders/b/bias_0.5.exr",
                  "scenes/b.scene.json engine:bias=1,cascades=4 renders/b/bias_1.exr"}));
    const SweepTask& image = p.tasks[3];
    EXPECT_TRUE(fs::path(image.image).is_absolute());
    EXPECT_EQ(image.technique, "engine");
    EXPECT_EQ(image.encoding, "linear");
    ASSERT_EQ(image.swept.size(), 1u) << "cascades has one value: not swept";
    EXPECT_EQ(image.swept[0], (std::pair<std::string, double>{"bias", 1.0}));
    // The task's line reads back as it was written (tasks.jsonl).
    fs::create_directories(dir_ / "out");
    writePlan(dir_ / "out", p);
    const SweepTask back = readPlanTask(dir_ / "out", readPlan(dir_ / "out", false), 3);
    EXPECT_EQ(back.image, image.image);
    EXPECT_EQ(back.encoding, image.encoding);
    EXPECT_EQ(back.label, image.label);

    // Images alone, on the scenes an entry names, with its encoding.
    const SweepPlan only =
        planSweepText(spec(R"([{"name": "engine", "path": "renders/{scene}/bias_{bias}.exr",
                  "params": {"bias": 1}, "scenes": ["scenes/b*"], "encoding": "srgb"}])"),
                      dir_ / "spec.json", validate);
    ASSERT_EQ(only.tasks.size(), 1u);
    EXPECT_EQ(only.scenes[only.tasks[0].scene].name, "scenes/b.scene.json");
    EXPECT_EQ(only.tasks[0].encoding, "srgb");
    EXPECT_EQ(only.tasks[0].label, "engine:bias=1");
}

TEST_F(SweepSpecImages, MistakesNameTheEntryAndTheField) {
    const std::string file = (dir_ / "spec.json").string();
    const std::string path = R"("path": "renders/{scene}/bias_{bias}.exr")";
    const auto entry = [&](const std::string& body) { return spec("[{" + body + "}]"); };
    const std::vector<std::pair<std::string, std::string>> cases = {
        {entry(R"("name": "engine", "path": "renders/{scene}/bias_{bias}.exr",
                   "params": {"bias": [0.5, 1, 2]})"),
         "images[0].path: no such image for engine:bias=2 on scenes/a.scene.json: " +
             (dir_ / "renders" / "a" / "bias_2.exr").string()},
        {entry(R"("name": "shadow", )" + path + R"(, "params": {"bias": 1})"),
         "images[0].name: \"shadow\" is a built-in technique"},
        {entry(R"("name": "my:engine", )" + path), "images[0].name: must be 1 to 64 of"},
        {entry(R"("name": "engine", )" + path + R"(, "params": {"bias": ["low"]})"),
         "images[0].params.bias[0]: expected a number, got a string"},
        {entry(R"("name": "engine", "path": "renders/{scene}/bias_{nope}.exr")"),
         "images[0].path: {nope} is neither {scene} nor a parameter"},
        {entry(R"("name": "engine", "path": "renders/{scene/bias.exr")"),
         "images[0].path: a '{' without its '}'"},
        {entry(R"("name": "engine", "path": "renders/scene}/bias.exr")"),
         "images[0].path: a '}' without its '{'"},
        {entry(R"("name": "engine")"), "images[0].path: must be the image's path"},
        {entry(R"("path": "x.exr")"), "images[0].name: must be the renderer's name"},
        {entry(R"("name": "engine", )" + path + R"(, "params": {"bias": 1}, "encoding": "gamma")"),
         "images[0].encoding: unknown encoding \"gamma\" (valid: linear, srgb)"},
        {entry(R"("name": "engine", )" + path + R"(, "params": {"bias": 1}, "scenes": ["x*"])"),
         "images[0].scenes[0]: matches none of the sweep's scenes: x*"},
        {entry(R"("name": "engine", )" + path + R"(, "params": {"bias": 1, "a=b": 2})"),
         "images[0].params.a=b: a parameter's name must be"},
        {entry(R"("name": "engine", )" + path + R"(, "params": {"bias": 1}, "size": 3)"),
         "images[0].size: unknown key"},
        {spec("[]"), "images: must be a non-empty list"},
        {R"({"sweep_format": 1, "scenes": ["scenes/a.scene.json"]})",
         "techniques: must be a non-empty list of {\"name\", \"params\"} (or give \"images\")"},
    };
    for (const auto& [text, expected] : cases) {
        const std::string e = error(text);
        EXPECT_EQ(e.rfind(file + ": ", 0), 0u) << text << "\n -> " << e;
        EXPECT_NE(e.find(expected), std::string::npos) << text << "\n -> " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
    }
}

// A row remembers the bytes of its image and cost file: another render, or none, makes it stale.
TEST_F(SweepSpecImages, ARowIsStaleWhenItsImageOrCostFileChanges) {
    const SweepPlan p =
        planSweepText(spec(R"([{"name": "engine", "path": "renders/{scene}/bias_{bias}.exr",
                  "params": {"bias": 1}, "scenes": ["scenes/a.scene.json"]}])"),
                      dir_ / "spec.json", validate);
    ASSERT_EQ(p.tasks.size(), 1u);
    const SweepTask& t = p.tasks[0];
    const nlohmann::json row = {
        {"task", {{"image", {{"path", t.image}, {"hash", imageInputsHash(t.image)}}}}}};
    EXPECT_FALSE(imageRowIsStale(row, t));
    EXPECT_TRUE(imageRowIsStale(nlohmann::json::object(), t)) << "a row without the image's hash";
    EXPECT_TRUE(imageRowIsStale(nlohmann::json("not a row"), t));
    std::ofstream(t.image + ".json") << R"({"frame_ms": 2})";
    EXPECT_TRUE(imageRowIsStale(row, t)) << "a cost file counts";
    fs::remove(t.image + ".json");
    EXPECT_FALSE(imageRowIsStale(row, t));
    std::ofstream(t.image) << "re-rendered";
    EXPECT_TRUE(imageRowIsStale(row, t));
    fs::remove(t.image);
    EXPECT_TRUE(imageRowIsStale(row, t)) << "gone";
    SweepTask technique = t;
    technique.image.clear();
    EXPECT_FALSE(imageRowIsStale(nlohmann::json::object(), technique));
}

// The sweep spec's trace keys are the trace option table's sweep rows (core/trace_option_table.h):
// each is accepted with a valid value and refused out of range, naming its field; the others are
// unknown keys.
TEST_F(SweepSpec, TraceOptionTableSweepKeysAreTheSpecsKeys) {
    const std::string head = R"({"sweep_format": 1, "scenes": ["scenes/a.scene.json"], )"
                             R"("techniques": [{"name": "shadow"}])";
    size_t offered = 0;
    for (const TraceOptionSpec& s : traceOptionTable()) {
        const bool top = s.key == "width" || s.key == "height";
        const std::string field = top ? s.key : "oracle." + s.key;
        const auto spec = [&](const std::string& value) {
            return head +
                   (top ? ", \"" + s.key + "\": " + value
                        : R"(, "oracle": {")" + s.key + "\": " + value + "}") +
                   "}";
        };
        const std::string def = s.type == TraceOptionType::Name
                                    ? "\"" + s.defaultValue.text + "\""
                                    : (s.unsetZero ? std::to_string(int64_t(s.max))
                                                   : nlohmann::json(s.defaultValue.number).dump());
        const std::string bad = s.type == TraceOptionType::Name ? "\"nope\"" : "-1";
        if (!(s.surfaces & kSurfaceSweep)) {
            EXPECT_NE(error(spec(def)).find(field + ": unknown key"), std::string::npos) << s.key;
            continue;
        }
        ++offered;
        EXPECT_EQ(error(spec(def)), "") << s.key;
        const std::string e = error(spec(bad));
        EXPECT_NE(e.find(": " + field + ": "), std::string::npos) << s.key << " -> " << e;
        if (!top) {
            SweepOracleSettings o = plan(R"([{"name": "shadow"}])", R"(["scenes/a.scene.json"])",
                                         R"(, "oracle": {")" + s.key + "\": " + def + "}")
                                        .settings.oracle;
            EXPECT_EQ(o.values.count(s.key), 1u) << s.key;
        }
    }
    EXPECT_GE(offered, 10u);
}

// The raster and comparison tables' sweep rows are the spec's top-level keys, checked by their
// rows; the others are unknown keys.
TEST_F(SweepSpec, RasterAndCompareTableSweepKeysAreTheSpecsKeys) {
    const std::string head = R"({"sweep_format": 1, "scenes": ["scenes/a.scene.json"], )"
                             R"("techniques": [{"name": "shadow"}])";
    size_t offered = 0;
    for (const OptionTable* table : {&rasterOptionTable(), &compareOptionTable()})
        for (const OptionSpec& s : table->rows) {
            const auto spec = [&](const std::string& value) {
                return head + ", \"" + s.key + "\": " + value + "}";
            };
            // A flag is a JSON boolean; any other row a number.
            const bool flag = s.type == OptionType::Flag;
            const std::string def = flag ? "true" : nlohmann::json(int64_t(s.max)).dump();
            if (!(s.surfaces & kSurfaceSweep)) {
                EXPECT_NE(error(spec(def)).find(s.key + ": unknown key"), std::string::npos)
                    << s.key;
                continue;
            }
            ++offered;
            EXPECT_EQ(error(spec(def)), "") << s.key;
            const std::string e = error(spec(flag ? "1" : "-1"));
            EXPECT_NE(e.find(": " + s.key + (flag ? ": " : ": must be an integer in")),
                      std::string::npos)
                << s.key << " -> " << e;
            const SweepSettings settings =
                plan(R"([{"name": "shadow"}])", R"(["scenes/a.scene.json"])",
                     ", \"" + s.key + "\": " + def)
                    .settings;
            const OptionValues& values =
                table == &rasterOptionTable() ? settings.raster : settings.compare;
            ASSERT_EQ(values.count(s.key), 1u) << s.key;
            EXPECT_EQ(values.at(s.key).number, s.max) << s.key;
        }
    EXPECT_GE(offered, 4u);  // frames, boundary_radius, sequence, converge
}

// What the command line refuses together (OptionSpec::excludes) a spec refuses too, by its keys.
TEST_F(SweepSpec, ConvergeWithASequenceIsOneOrTheOther) {
    const std::string head = R"({"sweep_format": 1, "scenes": ["scenes/a.scene.json"], )"
                             R"("techniques": [{"name": "shadow"}], "converge": 8)";
    EXPECT_EQ(error(head + "}"), "");
    EXPECT_EQ(error(head + R"(, "sequence": false})"), "");
    const std::string e = error(head + R"(, "sequence": true})");
    EXPECT_NE(e.find(": converge: not with sequence"), std::string::npos) << e;
}

}  // namespace
}  // namespace so
