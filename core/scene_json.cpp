// The scene file parser (docs/scene-format.md, scene_format 1 to newestSceneFormat()) and
// loadScene's dispatch. Strict on purpose: an unknown key is almost always a typo that would
// otherwise silently change what is measured, so every object lists the keys it accepts.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/camera.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/hash.h"
#include "core/json_reader.h"
#include "core/light_path.h"
#include "core/lights/light_kind.h"
#include "core/lights/make_light.h"
#include "core/read_file.h"
#include "core/scene.h"

namespace so {

namespace {

using Reader = JsonReader;

// The newest version read; every older one still loads. 2 added camera_path, 3 geometry[i].dynamic,
// 4 polygon lights, 5 sequence (glTF animations, light_paths); a light type that came with a newer
// version says so (LightKind::sceneFormat), and that version is then the newest.
int newestSceneFormat() {
    int newest = 5;
    for (const LightKind* k : allLightKinds()) newest = std::max(newest, k->sceneFormat());
    return newest;
}

// "rect, disk, ...": the area light types, for the warnings.
std::string areaLightNames() {
    std::string list;
    for (const LightKind* k : allLightKinds())
        if (k->isArea()) list += (list.empty() ? "" : ", ") + std::string(k->name());
    return list;
}

// Parses JSON and rejects duplicate keys in any object, which nlohmann would silently resolve to
// the last one.
json parseStrict(const std::string& text, const Reader& r) {
    std::vector<std::set<std::string>> keysPerDepth;
    std::string duplicate;
    auto callback = [&](int depth, json::parse_event_t event, json& parsed) {
        if (event == json::parse_event_t::object_start) {
            if (keysPerDepth.size() <= size_t(depth)) keysPerDepth.resize(depth + 1);
            keysPerDepth[depth].clear();
        } else if (event == json::parse_event_t::key && duplicate.empty()) {
            // Keys are reported at the depth of the object that owns them.
            size_t d = size_t(depth > 0 ? depth - 1 : 0);
            if (keysPerDepth.size() <= d) keysPerDepth.resize(d + 1);
            if (!keysPerDepth[d].insert(parsed.get<std::string>()).second)
                duplicate = parsed.get<std::string>();
        }
        return true;
    };
    json j;
    try {
        j = json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/false);
    } catch (const json::parse_error& e) {
        // nlohmann's message already names line and column; keep its last clause on one line.
        std::string what = e.what();
        auto pos = what.find("parse error");
        r.fail("", "invalid JSON: " +
                       printable(pos == std::string::npos ? what : what.substr(pos), 160));
    } catch (const json::out_of_range& e) {
        // A number beyond double range (1e999): nlohmann names the literal but not where it is.
        std::string what = e.what();
        auto q1 = what.find('\''), q2 = what.rfind('\'');
        std::string literal =
            q1 != std::string::npos && q2 > q1 ? what.substr(q1 + 1, q2 - q1 - 1) : "";
        std::string where;
        if (auto at = literal.empty() ? std::string::npos : text.find(literal);
            at != std::string::npos) {
            size_t line = 1 + size_t(std::count(text.begin(), text.begin() + long(at), '\n'));
            size_t lineStart = text.rfind('\n', at);
            size_t column = at - (lineStart == std::string::npos ? 0 : lineStart + 1) + 1;
            where = "line " + std::to_string(line) + ", column " + std::to_string(column) + ": ";
        }
        r.fail("",
               "invalid JSON: " + where + "number " + printable(literal, 40) + " is not finite");
    } catch (const json::exception& e) {
        r.fail("", "invalid JSON: " + printable(e.what(), 160));
    }
    if (!duplicate.empty()) r.fail(printable(duplicate, 40), "duplicate key");
    return j;
}

// A geometry path must stay inside the scene file's folder (no absolute paths, no "..").
std::filesystem::path resolveInside(const std::filesystem::path& folder, const std::string& rel,
                                    const Reader& r, const std::string& field) {
    if (rel.empty()) r.fail(field, "empty path");
    if (rel.find('\0') != std::string::npos) r.fail(field, "path contains a NUL byte");
    std::filesystem::path p(rel);
    if (p.is_absolute() || p.has_root_name() || p.has_root_directory())
        r.fail(field, "absolute paths are not allowed (paths are relative to the scene file)");
    // "scheme:..." (http:, file:, data:...) is a URL, not a path.
    auto colon = rel.find(':');
    if (colon != std::string::npos && colon > 0 &&
        std::all_of(rel.begin(), rel.begin() + long(colon), [](char c) {
            return std::isalnum((unsigned char)c) || c == '+' || c == '-' || c == '.';
        }))
        r.fail(field, "URLs are not allowed (paths are relative to the scene file)");
    for (const auto& part : p.lexically_normal())
        if (part == "..") r.fail(field, "path leaves the scene's folder");
    return folder / p;
}

struct Loaded {
    Scene scene;
    std::vector<std::pair<std::filesystem::path, std::string>> files;  // for the hash
};

void parseLights(const json& jl, const Reader& r, const LoadLimits& limits, Scene& scene) {
    r.requireArray(jl, "lights");
    if (jl.empty()) r.fail("lights", "a scene needs at least one light");
    if (jl.size() > limits.maxLights)
        r.fail("lights",
               std::to_string(jl.size()) + " lights, limit is " + std::to_string(limits.maxLights));
    std::set<std::string> names;
    for (size_t i = 0; i < jl.size(); ++i) {
        std::string f = Reader::index("lights", i);
        const json& j = jl[i];
        r.requireObject(j, f);
        if (!j.contains("type")) r.fail(f + ".type", "missing");
        if (!j.contains("name")) r.fail(f + ".name", "missing");
        Light light;
        light.name = r.string(j["name"], f + ".name");
        if (!channels::isValidLayerName(light.name))
            r.fail(f + ".name", "\"" + printable(light.name, 40) +
                                    "\" is not a valid layer name (1-64 of [A-Za-z0-9_-], starting "
                                    "with a letter or '_', not P, N, id, A or Z)");
        if (!names.insert(light.name).second)
            r.fail(f + ".name", "duplicate light name \"" + light.name + "\"");
        std::string type = r.string(j["type"], f + ".type");
        const LightKind* kind = findLightKind(type);
        if (!kind)
            r.fail(f + ".type", "unknown light type \"" + printable(type, 40) +
                                    "\" (valid: " + lightKindNames() + ")");
        std::vector<std::string> keys = kind->keys();
        keys.insert(keys.begin(), {"name", "type"});
        r.checkKeys(j, f, keys, std::string(" for a ") + kind->name() + " light");
        light.type = kind->type();
        kind->parse(j, r, f, light);
        scene.lights.push_back(light);
    }
}

CameraDesc parseCamera(const json& j, const Reader& r, const LoadLimits& limits, bool& given) {
    CameraDesc c;
    given = true;
    r.requireObject(j, "camera");
    r.checkKeys(j, "camera", {"eye", "target", "up", "vfov_deg", "width", "height"});
    if (!j.contains("eye")) r.fail("camera.eye", "missing");
    if (!j.contains("target")) r.fail("camera.target", "missing");
    c.wsEye = r.vec3(j["eye"], "camera.eye");
    c.wsTarget = r.vec3(j["target"], "camera.target");
    if (j.contains("up")) c.wsUp = r.vec3(j["up"], "camera.up");
    if (j.contains("vfov_deg")) c.vfovDeg = r.number(j["vfov_deg"], "camera.vfov_deg");
    if (j.contains("width"))
        c.width = r.integer(j["width"], "camera.width", 1, limits.maxImageSide);
    if (j.contains("height"))
        c.height = r.integer(j["height"], "camera.height", 1, limits.maxImageSide);
    if (!(c.vfovDeg > 0.0 && c.vfovDeg < 180.0))
        r.outOfRange("camera.vfov_deg", "in (0, 180)", c.vfovDeg);
    glm::dvec3 forward = c.wsTarget - c.wsEye;
    if (!(glm::length(forward) > 0.0)) r.fail("camera.target", "equals camera.eye");
    if (!(glm::length(c.wsUp) > 0.0)) r.fail("camera.up", "zero length");
    double s = glm::length(glm::cross(glm::normalize(forward), glm::normalize(c.wsUp)));
    if (!(s > 1e-9)) r.fail("camera.up", "parallel to the viewing direction");
    if (uint64_t(c.width) * uint64_t(c.height) > limits.maxImagePixels)
        r.fail("camera.width", "image of " + std::to_string(c.width) + "x" +
                                   std::to_string(c.height) + " exceeds the pixel limit " +
                                   std::to_string(limits.maxImagePixels));
    return c;
}

// The same rules as the scene camera: eye and target differ, up is not parallel to the view.
void checkPose(const glm::dvec3& wsEye, const glm::dvec3& wsTarget, const glm::dvec3& wsUp,
               const Reader& r, const std::string& f) {
    glm::dvec3 forward = wsTarget - wsEye;
    if (!(glm::length(forward) > 0.0)) r.fail(f + ".target", "equals eye");
    if (!(glm::length(wsUp) > 0.0)) r.fail(f + ".up", "zero length");
    double s = glm::length(glm::cross(glm::normalize(forward), glm::normalize(wsUp)));
    if (!(s > 1e-9)) r.fail(f + ".up", "parallel to the viewing direction");
}

// One keyframe or pose; `hasT`: keyframes carry their t, poses are numbered.
CameraKeyframe parsePathPose(const json& j, const Reader& r, const std::string& f, bool hasT,
                             const CameraDesc& base) {
    r.requireObject(j, f);
    if (hasT)
        r.checkKeys(j, f, {"t", "eye", "target", "up", "vfov_deg"});
    else
        r.checkKeys(j, f, {"eye", "target", "up", "vfov_deg"});
    CameraKeyframe k;
    if (hasT) {
        if (!j.contains("t")) r.fail(f + ".t", "missing");
        k.t = r.number(j["t"], f + ".t");
    }
    if (!j.contains("eye")) r.fail(f + ".eye", "missing");
    if (!j.contains("target")) r.fail(f + ".target", "missing");
    k.wsEye = r.vec3(j["eye"], f + ".eye");
    k.wsTarget = r.vec3(j["target"], f + ".target");
    if (j.contains("up")) k.wsUp = r.vec3(j["up"], f + ".up");
    if (j.contains("vfov_deg")) {
        k.vfovDeg = r.number(j["vfov_deg"], f + ".vfov_deg");
        if (!(*k.vfovDeg > 0.0 && *k.vfovDeg < 180.0))
            r.outOfRange(f + ".vfov_deg", "in (0, 180)", *k.vfovDeg);
    }
    checkPose(k.wsEye, k.wsTarget, k.wsUp.value_or(base.wsUp), r, f);
    return k;
}

// camera_path (scene_format 2): {"keyframes": [...], "interpolation": ...} or {"poses": [...]}.
CameraPath parseCameraPath(const json& j, const Reader& r, const LoadLimits& limits,
                           const CameraDesc& base) {
    r.requireObject(j, "camera_path");
    r.checkKeys(j, "camera_path", {"keyframes", "interpolation", "poses"});
    const bool keyed = j.contains("keyframes");
    if (keyed == j.contains("poses"))
        r.fail("camera_path", "needs exactly one of keyframes or poses");
    if (!keyed && j.contains("interpolation"))
        r.fail("camera_path.interpolation", "only with keyframes (poses are used in order)");
    CameraPath path;
    path.file = r.file();
    const std::string list = keyed ? "camera_path.keyframes" : "camera_path.poses";
    const json& jk = keyed ? j["keyframes"] : j["poses"];
    r.requireArraySize(jk, list, 2, limits.maxPathKeyframes);
    for (size_t i = 0; i < jk.size(); ++i) {
        const std::string f = Reader::index(list, i);
        CameraKeyframe k = parsePathPose(jk[i], r, f, keyed, base);
        if (!keyed) k.t = double(i);
        if (i > 0 && !(k.t > path.keyframes.back().t))
            r.fail(f + ".t", "not greater than the previous keyframe's t");
        path.keyframes.push_back(k);
    }
    if (j.contains("interpolation")) {
        const std::string how = r.string(j["interpolation"], "camera_path.interpolation");
        if (how == "linear")
            path.interpolation = PathInterpolation::Linear;
        else if (how == "catmull-rom")
            path.interpolation = PathInterpolation::CatmullRom;
        else
            r.fail("camera_path.interpolation", "unknown interpolation \"" + printable(how, 40) +
                                                    "\" (valid: linear, catmull-rom)");
    }
    return path;
}

// geometry[i].dynamic (scene_format 3): true marks the entry's meshes as moving, which only a
// lightmap heeds (it leaves them out of its bake); absent is false.
bool parseDynamic(const json& j, const Reader& r, const std::string& field, int format) {
    if (!j.contains("dynamic")) return false;
    const std::string f = field + ".dynamic";
    if (format < 3)
        r.fail(f, "needs scene_format 3 (the file says " + std::to_string(format) + ")");
    return r.boolean(j["dynamic"], f);
}

void addGltf(Scene& scene, const GltfContent& g, uint64_t& totalBytes, const LoadLimits& limits,
             const std::string& display) {
    totalBytes += g.bytesRead;
    if (totalBytes > limits.maxTotalBytes)
        throwInputError(
            display, "",
            "the scene's files total more than " + std::to_string(limits.maxTotalBytes) + " bytes");
    // Each file numbers its textures from 0; the scene's list holds every file's in turn.
    const int textureBase = int(scene.alphaTextures.size());
    for (const MeshPrimitive& m : g.meshes) {
        scene.meshes.push_back(m);
        if (m.alpha && m.alpha->texture >= 0) scene.meshes.back().alpha->texture += textureBase;
    }
    uint64_t texturePixels = 0;
    for (const AlphaTexture& t : scene.alphaTextures) texturePixels += t.alpha.size();
    for (const AlphaTexture& t : g.alphaTextures) {
        texturePixels += t.alpha.size();
        scene.alphaTextures.push_back(t);
    }
    if (texturePixels > limits.maxTotalImagePixels)
        throwInputError(display, "geometry",
                        "the alpha textures hold " + std::to_string(texturePixels) +
                            " pixels in all, over the limit of " +
                            std::to_string(limits.maxTotalImagePixels));
    if (scene.meshes.size() > limits.maxMeshes)
        throwInputError(display, "",
                        "more than " + std::to_string(limits.maxMeshes) + " drawn meshes");
    scene.stats.skippedPrimitives += g.skippedPrimitives;
    std::vector<std::string>& ignored = scene.stats.gltfExtensionsIgnored;
    for (const std::string& e : g.gltfExtensionsIgnored)
        if (std::find(ignored.begin(), ignored.end(), e) == ignored.end()) ignored.push_back(e);
    std::sort(ignored.begin(), ignored.end());
    for (const std::string& w : g.warnings) scene.stats.warnings.push_back(w);
}

// A scene that asks for something its lights cannot show, or has lights that its effects leave
// cheap, is told so: silence would read as "simulated".
void warnAboutEffects(Scene& scene) {
    bool anyArea = false;
    for (const Light& l : scene.lights) anyArea |= isAreaLight(l.type);
    size_t masked = 0;
    for (const MeshPrimitive& m : scene.meshes) masked += m.alpha.has_value();
    if (scene.hasEffect("alpha") && masked == 0)
        scene.stats.warnings.push_back(
            "effects: \"alpha\" is listed but no material is alpha-tested (MASK or BLEND): "
            "nothing to test");
    if (!scene.hasEffect("alpha") && masked > 0)
        scene.stats.warnings.push_back(
            std::to_string(masked) +
            " alpha-tested primitive(s) drawn opaque: effects lacks \"alpha\"");
    if (scene.hasEffect("penumbra") && !anyArea)
        scene.stats.warnings.push_back(
            "effects: \"penumbra\" is listed but the scene has no area light (" + areaLightNames() +
            "): nothing to sample");
    if (!scene.hasEffect("penumbra"))
        for (const Light& l : scene.lights)
            if (isAreaLight(l.type))
                scene.stats.warnings.push_back(
                    "light \"" + l.name + "\" is a " + lightTypeName(l.type) +
                    " light but effects lacks \"penumbra\": traced as a point "
                    "light at its centre");
}

std::vector<std::string> parseEffects(const json& root, const Reader& r) {
    if (!root.contains("effects")) return {"hard"};
    const json& je = root["effects"];
    if (!je.is_array())
        r.fail("effects", "expected an array of strings, got " + Reader::typeName(je));
    std::vector<std::string> effects;
    std::set<std::string> seen;
    for (size_t i = 0; i < je.size(); ++i) {
        std::string f = Reader::index("effects", i);
        std::string e = r.string(je[i], f);
        if (e != "hard" && e != "penumbra" && e != "contact" && e != "alpha")
            r.fail(f, "unknown effect \"" + printable(e, 40) +
                          "\" (valid: hard, penumbra, contact, alpha)");
        if (!seen.insert(e).second) r.fail(f, "\"" + e + "\" listed twice");
        effects.push_back(e);
    }
    if (effects.empty()) r.fail("effects", "empty: nothing to simulate (omit it for [\"hard\"])");
    return effects;
}

// A light type that came with a newer scene_format (polygon: 4): an older file naming one is told
// so (a scene made in memory has no version and takes every type).
void checkLightFormats(const json& root, const Reader& r, int format) {
    if (!root.contains("lights") || !root["lights"].is_array()) return;
    const json& jl = root["lights"];
    for (size_t i = 0; i < jl.size(); ++i) {
        if (!jl[i].is_object() || !jl[i].contains("type") || !jl[i]["type"].is_string()) continue;
        const std::string name = jl[i]["type"].get<std::string>();
        const LightKind* kind = findLightKind(name);
        if (kind && kind->sceneFormat() > format)
            r.fail(Reader::index("lights", i) + ".type",
                   "\"" + name + "\" needs scene_format " + std::to_string(kind->sceneFormat()) +
                       " (the file says " + std::to_string(format) + ")");
    }
}

// What a scene file and a scene made in memory share once their meshes are in: the camera, the
// lights, the checks on the whole and the camera path. `geometryField` names the meshes' source
// in errors ("geometry" of a file, "meshes" in memory).
// sequence (scene_format 5): {"frames": N, "fps": F, "animation": "NAME"}; frame i is at i / F s.
Sequence parseSequence(const json& j, const Reader& r, const LoadLimits& limits) {
    r.requireObject(j, "sequence");
    r.checkKeys(j, "sequence", {"frames", "fps", "animation"});
    Sequence sequence;
    if (!j.contains("frames")) r.fail("sequence.frames", "missing");
    sequence.frames = r.integer(j["frames"], "sequence.frames", 1, limits.maxSequenceFrames);
    if (!j.contains("fps")) r.fail("sequence.fps", "missing");
    sequence.fps = r.numberIn(j["fps"], "sequence.fps", 1e-3, 1e6);
    if (j.contains("animation")) {
        sequence.animation = r.string(j["animation"], "sequence.animation");
        if (sequence.animation.empty())
            r.fail("sequence.animation", "empty (leave the key out to play every clip)");
    }
    return sequence;
}

void finishScene(const json& root, const Reader& r, const LoadLimits& limits,
                 const std::string& geometryField, Scene& scene) {
    bool cameraGiven = false;
    if (root.contains("camera")) scene.camera = parseCamera(root["camera"], r, limits, cameraGiven);

    if (!root.contains("lights")) r.fail("lights", "missing");
    parseLights(root["lights"], r, limits, scene);

    warnAboutEffects(scene);
    finalizeScene(scene);
    if (scene.stats.totalTrianglesExceeded(limits))
        r.fail(geometryField,
               "more than " + std::to_string(limits.maxTotalTriangles) + " triangles in all");
    if (!cameraGiven) {
        scene.camera = defaultFraming(scene.wsBounds);
        scene.stats.warnings.push_back("no camera given: using the default framing of the bounds");
    }
    // After the camera: a key without up takes the camera's, which must then suit its direction.
    // The path is part of the description's text, so the content hash already covers it.
    if (root.contains("camera_path"))
        scene.cameraPath = parseCameraPath(root["camera_path"], r, limits, scene.camera);
    if (root.contains("sequence") && !scene.sequence)
        scene.sequence = parseSequence(root["sequence"], r, limits);
    if (root.contains("light_paths")) {
        if (!scene.sequence)
            r.fail("light_paths", "needs a sequence (the clock its keys' t are read on)");
        scene.lightPaths = parseLightPaths(root["light_paths"], r, limits, scene.lights);
    }
}

// A sequence naming a clip: some geometry file must have it (the error lists the clips there are).
void checkClipFound(const Scene& scene, const std::vector<GltfContent>& files, const Reader& r) {
    if (!scene.sequence || scene.sequence->animation.empty()) return;
    std::string names;
    for (const GltfContent& g : files) {
        if (g.animationClipFound) return;
        for (const std::string& n : g.animationNames) names += (names.empty() ? "" : ", ") + n;
    }
    r.fail("sequence.animation",
           "no glTF animation named \"" + printable(scene.sequence->animation, 60) +
               "\" (the geometry has " + (names.empty() ? std::string("none") : names) + ")");
}

Scene loadSceneJson(const std::filesystem::path& path, const std::string& display,
                    const LoadLimits& limits) {
    Reader r(display);
    std::string text =
        readFileCapped(path, display, std::min<uint64_t>(limits.maxFileBytes, 64u << 20));
    json root = parseStrict(text, r);
    r.requireObject(root, "");
    r.checkKeys(root, "",
                {"scene_format", "geometry", "camera", "camera_path", "lights", "effects",
                 "sequence", "light_paths"});
    if (!root.contains("scene_format"))
        r.fail("scene_format",
               "missing (this tool reads 1 to " + std::to_string(newestSceneFormat()) + ")");
    int format = r.integer(root["scene_format"], "scene_format", 0, 1 << 30);
    if (format < 1 || format > newestSceneFormat())
        r.fail("scene_format", "unsupported version " + std::to_string(format) +
                                   " (this tool reads 1 to " + std::to_string(newestSceneFormat()) +
                                   ")");
    if (root.contains("camera_path") && format < 2)
        r.fail("camera_path",
               "needs scene_format 2 (the file says " + std::to_string(format) + ")");
    for (const char* key : {"sequence", "light_paths"})
        if (root.contains(key) && format < 5)
            r.fail(key, "needs scene_format 5 (the file says " + std::to_string(format) + ")");
    checkLightFormats(root, r, format);

    Scene scene;
    scene.path = path;
    ContentHasher hasher;
    hasher.add(text);
    std::filesystem::path folder = path.parent_path();
    uint64_t totalBytes = text.size();

    // Effects first: they decide what the geometry's files must hold (alpha textures); the
    // sequence too: it decides whether the files' animations play.
    scene.effects = parseEffects(root, r);
    if (root.contains("sequence")) scene.sequence = parseSequence(root["sequence"], r, limits);
    std::vector<GltfContent> loaded;  // only what checkClipFound reads is kept

    if (!root.contains("geometry")) r.fail("geometry", "missing");
    const json& jg = root["geometry"];
    r.requireArray(jg, "geometry");
    for (size_t i = 0; i < jg.size(); ++i) {
        std::string f = Reader::index("geometry", i);
        const json& j = jg[i];
        r.requireObject(j, f);
        r.checkKeys(j, f, {"file", "translate", "scale", "dynamic"});
        const bool dynamic = parseDynamic(j, r, f, format);
        if (!j.contains("file")) r.fail(f + ".file", "missing");
        std::string rel = r.string(j["file"], f + ".file");
        std::filesystem::path file = resolveInside(folder, rel, r, f + ".file");
        glm::dvec3 translate(0.0), scale(1.0);
        if (j.contains("translate")) translate = r.vec3(j["translate"], f + ".translate");
        if (j.contains("scale")) {
            scale = j["scale"].is_number() ? glm::dvec3(r.number(j["scale"], f + ".scale"))
                                           : r.vec3(j["scale"], f + ".scale");
            if (scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0)
                r.fail(f + ".scale", "zero scale flattens the geometry");
        }
        std::string ext = file.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
        if (ext != ".gltf" && ext != ".glb")
            r.fail(f + ".file", "\"" + printable(rel, 60) + "\" is not a .gltf or .glb file");
        glm::dmat4 wsFromFile = glm::scale(glm::translate(glm::dmat4(1.0), translate), scale);
        std::string gltfDisplay =
            (std::filesystem::path(display).parent_path() / rel).lexically_normal().string();
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec))
            r.fail(f + ".file", "\"" + printable(rel, 60) + "\": no such file");
        GltfContent g = loadGltf(file, gltfDisplay, wsFromFile, limits, scene.hasEffect("alpha"),
                                 scene.sequence ? &*scene.sequence : nullptr);
        for (MeshPrimitive& m : g.meshes) m.dynamic = dynamic;
        scene.geometry.push_back({std::filesystem::absolute(file, ec), translate, scale});
        for (const auto& fr : g.filesRead) {
            std::string relName = fr.lexically_relative(folder).generic_string();
            hasher.addFile(fr, relName);
        }
        addGltf(scene, g, totalBytes, limits, display);
        loaded.emplace_back();
        loaded.back().animationNames = std::move(g.animationNames);
        loaded.back().animationClipFound = g.animationClipFound;
    }
    checkClipFound(scene, loaded, r);
    if (jg.empty())
        scene.stats.warnings.push_back("the scene has no geometry: every pixel is background");

    finishScene(root, r, limits, "geometry", scene);
    scene.contentHash = hasher.hex();
    return scene;
}

Scene loadSceneGltf(const std::filesystem::path& path, const std::string& display,
                    const LoadLimits& limits) {
    GltfContent g = loadGltf(path, display, glm::dmat4(1.0), limits);
    Scene scene;
    scene.path = path;
    std::error_code ec;
    scene.geometry.push_back(
        {std::filesystem::absolute(path, ec), glm::dvec3(0.0), glm::dvec3(1.0)});
    uint64_t totalBytes = 0;
    addGltf(scene, g, totalBytes, limits, display);
    ContentHasher hasher;
    std::filesystem::path folder = path.parent_path();
    for (const auto& fr : g.filesRead)
        hasher.addFile(fr, fr.lexically_relative(folder).generic_string());
    scene.lights = g.lights;
    if (scene.lights.empty()) {
        scene.lights.push_back(
            directionalLight("sun", glm::normalize(glm::dvec3(-0.3, -1.0, -0.5))));
        scene.stats.warnings.push_back(
            "the glTF file has no KHR_lights_punctual lights: added the default directional light "
            "\"sun\" travelling along (-0.3, -1, -0.5)");
    }
    // A bare glTF file has no effects list: its alpha-tested materials are tested.
    scene.effects = {"hard"};
    for (const MeshPrimitive& m : scene.meshes)
        if (m.alpha) {
            scene.effects.push_back("alpha");
            break;
        }
    finalizeScene(scene);
    if (scene.stats.totalTrianglesExceeded(limits))
        throwInputError(
            display, "meshes",
            "more than " + std::to_string(limits.maxTotalTriangles) + " triangles in all");
    if (g.camera) {
        scene.camera = *g.camera;
    } else {
        scene.camera = defaultFraming(scene.wsBounds);
        scene.stats.warnings.push_back(
            "no camera in the glTF file: using the default framing of the bounds");
    }
    scene.contentHash = hasher.hex();
    return scene;
}

}  // namespace

Scene loadScene(const std::filesystem::path& path, const LoadLimits& limits) {
    std::string display = path.string();
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throwInputError(display, "", "no such file");
    if (ext == ".json") return loadSceneJson(path, display, limits);
    if (ext == ".gltf" || ext == ".glb") return loadSceneGltf(path, display, limits);
    throwInputError(
        display, "",
        "unknown scene file type \"" + printable(ext, 16) + "\" (expected .json, .gltf or .glb)");
}

}  // namespace so

namespace so {

namespace {

// The meshes of a scene made in memory: every index in range, every coordinate finite, within the
// file loader's limits.
void checkMeshes(const std::vector<MeshPrimitive>& meshes, const Reader& r,
                 const LoadLimits& limits) {
    if (meshes.size() > limits.maxMeshes)
        r.fail("meshes", "more than " + std::to_string(limits.maxMeshes) + " meshes");
    for (size_t m = 0; m < meshes.size(); ++m) {
        const MeshPrimitive& mesh = meshes[m];
        const std::string f = Reader::index("meshes", m);
        if (mesh.indices.size() % 3 != 0)
            r.fail(f + ".triangles", "the index count is not a multiple of 3");
        if (mesh.triangleCount() > limits.maxTrianglesPerMesh)
            r.fail(f + ".triangles",
                   "more than " + std::to_string(limits.maxTrianglesPerMesh) + " triangles");
        for (size_t i = 0; i < mesh.indices.size(); ++i)
            if (mesh.indices[i] >= mesh.wsPositions.size())
                r.fail(f + ".triangles", "index " + std::to_string(mesh.indices[i]) + " at " +
                                             std::to_string(i) + " is past the " +
                                             std::to_string(mesh.wsPositions.size()) + " vertices");
        for (size_t v = 0; v < mesh.wsPositions.size(); ++v) {
            const glm::dvec3& p = mesh.wsPositions[v];
            if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
                r.fail(f + ".vertices", "vertex " + std::to_string(v) + " is not finite");
        }
    }
}

}  // namespace

Scene sceneFromMemory(const std::string& description, std::vector<MeshPrimitive> meshes,
                      const std::string& display, const LoadLimits& limits) {
    Reader r(display);
    json root = parseStrict(description, r);
    r.requireObject(root, "");
    r.checkKeys(root, "", {"camera", "camera_path", "lights", "effects"});
    Scene scene;
    scene.effects = parseEffects(root, r);
    checkMeshes(meshes, r, limits);
    ContentHasher hasher;
    hasher.add(description);
    for (const MeshPrimitive& mesh : meshes) {
        hasher.add(std::string_view(reinterpret_cast<const char*>(mesh.wsPositions.data()),
                                    mesh.wsPositions.size() * sizeof(glm::dvec3)));
        hasher.add(std::string_view(reinterpret_cast<const char*>(mesh.indices.data()),
                                    mesh.indices.size() * sizeof(uint32_t)));
    }
    scene.meshes = std::move(meshes);
    finishScene(root, r, limits, "meshes", scene);
    scene.contentHash = hasher.hex();
    return scene;
}

}  // namespace so
