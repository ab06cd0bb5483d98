#include "core/light_path.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/lights/light_kind.h"

namespace so {
namespace {

LightKeyframe parseKey(const json& j, const JsonReader& r, const std::string& f,
                       const LightKind& kind) {
    r.requireObject(j, f);
    r.checkKeys(j, f, {"t", "position", "direction"});
    LightKeyframe k;
    if (!j.contains("t")) r.fail(f + ".t", "missing");
    k.t = r.number(j["t"], f + ".t");
    if (j.contains("position")) {
        if (!kind.pathMovesPosition())
            r.fail(f + ".position",
                   std::string("a ") + kind.name() + " light has no position (give a direction)");
        k.wsPosition = r.vec3(j["position"], f + ".position");
    }
    if (j.contains("direction")) {
        if (!kind.pathTurnsDirection())
            r.fail(f + ".direction", std::string("a ") + kind.name() +
                                         " light has no direction to turn (give a position)");
        k.wsDirection = r.unitVec3(j["direction"], f + ".direction");
    }
    if (!k.wsPosition && !k.wsDirection) r.fail(f, "needs a position or a direction");
    return k;
}

LightPath parsePath(const json& j, const JsonReader& r, const LoadLimits& limits,
                    const std::string& f, const LightKind& kind) {
    r.requireObject(j, f);
    r.checkKeys(j, f, {"keyframes", "interpolation"});
    LightPath path;
    const std::string list = f + ".keyframes";
    if (!j.contains("keyframes")) r.fail(list, "missing");
    const json& jk = j["keyframes"];
    r.requireArraySize(jk, list, 2, limits.maxPathKeyframes);
    for (size_t i = 0; i < jk.size(); ++i) {
        const std::string fk = JsonReader::index(list, i);
        LightKeyframe k = parseKey(jk[i], r, fk, kind);
        if (i > 0 && !(k.t > path.keyframes.back().t))
            r.fail(fk + ".t", "not greater than the previous keyframe's t");
        if (i > 0 && (k.wsPosition.has_value() != path.keyframes[0].wsPosition.has_value() ||
                      k.wsDirection.has_value() != path.keyframes[0].wsDirection.has_value()))
            r.fail(fk, "sets other fields than keyframes[0] (every key sets the same ones)");
        path.keyframes.push_back(k);
    }
    if (j.contains("interpolation")) {
        const std::string how = r.string(j["interpolation"], f + ".interpolation");
        if (how == "linear")
            path.interpolation = PathInterpolation::Linear;
        else if (how == "catmull-rom")
            path.interpolation = PathInterpolation::CatmullRom;
        else
            r.fail(f + ".interpolation", "unknown interpolation \"" + printable(how, 40) +
                                             "\" (valid: linear, catmull-rom)");
    }
    return path;
}

// One of a key's vectors along the path at t, as camera_path interpolates (core/camera_path.cpp):
// linear, or Catmull-Rom with tangents from the neighbours' differences over their t.
template <typename Get>
glm::dvec3 interpolate(const LightPath& path, double t, Get get) {
    const std::vector<LightKeyframe>& keys = path.keyframes;
    t = std::clamp(t, keys.front().t, keys.back().t);
    size_t i = 0;
    while (i + 2 < keys.size() && t >= keys[i + 1].t) ++i;
    const double t1 = keys[i].t, t2 = keys[i + 1].t, s = (t - t1) / (t2 - t1);
    const glm::dvec3 a = get(keys[i]), b = get(keys[i + 1]);
    if (s <= 0.0) return a;  // the keys exactly, whatever the arithmetic would round to
    if (s >= 1.0) return b;
    if (path.interpolation == PathInterpolation::Linear) return a + s * (b - a);
    auto tangent = [&](size_t k) {
        const size_t lo = k == 0 ? 0 : k - 1, hi = std::min(k + 1, keys.size() - 1);
        return (get(keys[hi]) - get(keys[lo])) / (keys[hi].t - keys[lo].t);
    };
    const double s2 = s * s, s3 = s2 * s, dt = t2 - t1;
    return (2 * s3 - 3 * s2 + 1) * a + (s3 - 2 * s2 + s) * dt * tangent(i) +
           (-2 * s3 + 3 * s2) * b + (s3 - s2) * dt * tangent(i + 1);
}

}  // namespace

std::vector<LightPath> parseLightPaths(const json& j, const JsonReader& r, const LoadLimits& limits,
                                       const std::vector<Light>& lights) {
    r.requireObject(j, "light_paths");
    std::vector<LightPath> paths;
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string f = "light_paths." + printable(it.key(), 64);
        auto light = std::find_if(lights.begin(), lights.end(),
                                  [&](const Light& l) { return l.name == it.key(); });
        if (light == lights.end()) r.fail(f, "names no light of the scene");
        LightPath path = parsePath(it.value(), r, limits, f, lightKind(light->type));
        path.light = light->name;
        paths.push_back(std::move(path));
    }
    return paths;
}

Light lightAt(const LightPath& path, const Light& light, double t) {
    Light posed = light;
    if (path.keyframes.front().wsPosition) {
        const glm::dvec3 delta =
            interpolate(path, t, [](const LightKeyframe& k) { return *k.wsPosition; }) -
            light.wsPosition;
        posed.wsPosition += delta;
        for (glm::dvec3& v : posed.wsVertices) v += delta;
    }
    if (path.keyframes.front().wsDirection) {
        const glm::dvec3 d =
            interpolate(path, t, [](const LightKeyframe& k) { return *k.wsDirection; });
        const double len = glm::length(d);
        if (len > 1e-9) {
            posed.wsDirection = d / len;
        } else {  // opposite keys halfway: the nearer key's direction
            const LightKeyframe* nearest = &path.keyframes.front();
            for (const LightKeyframe& k : path.keyframes)
                if (std::abs(k.t - t) < std::abs(nearest->t - t)) nearest = &k;
            posed.wsDirection = *nearest->wsDirection;
        }
    }
    return posed;
}

}  // namespace so
