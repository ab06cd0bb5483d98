// A technique's parameters: one table per technique (name, default, range, meaning) that is the
// single source of its validation, of `shadow-oracle techniques` and of docs/techniques.md.
//
// Lengths in parameters are in texels: multiples of the world-space size of one shadow-map texel
// at the receiver, so the same setting means the same thing at any scene scale or resolution.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "raster_compare/gl/provenance.h"

namespace so {

// A name a parameter had before (raytraced's `alpha`, now `history`): a setting that gives it is
// still accepted, converted and said once as a deprecation notice, for one version.
struct FormerName {
    std::string name;
    // The value under the former name to the current one (history = 1 - alpha); empty: the same.
    std::function<double(double)> toCurrent = {};
    // How the two relate, for the notice ("history = 1 - alpha"); empty: the same meaning.
    std::string relation = {};
    // The `techniques --json` format_version that stops accepting it.
    int untilFormat = 0;
};

// A name one of a method parameter's values had before (`denoiser=penumbra`, now `hitdist`): a
// setting that gives it is still accepted as the current value and said once as a deprecation
// notice, until that format.
struct FormerValue {
    std::string name;     // "penumbra"
    std::string current;  // "hitdist": one of the parameter's names
    // The `techniques --json` format_version that stops accepting it.
    int untilFormat = 0;
};

struct ParamSpec {
    std::string name;
    double defaultValue;
    double min, max;
    bool integer;
    std::string doc;
    std::vector<double> allowed = {};  // when not empty: the only valid values
    // The technique's main quality parameter (at most one per table): the report draws the
    // settings that differ only in it as one curve of error against cost.
    bool quality = false;
    // A parameter that picks a method: the names of its values 0, 1, ... (made by methodParam).
    // A setting gives the name ("pattern=poisson") or, as before names, the number.
    std::vector<std::string> names = {};
    // The range is [min, max): max itself is out of range (a blend weight below 1).
    bool maxExclusive = false;
    // "key=value": the setting this parameter means nothing without (resolve needs temporal=on);
    // "key=a|b": any of those values. Given without it, an InputError rather than
    // silently doing nothing. Needs chain: the key's own needs must hold too.
    std::string needs = {};
    // A parameter of one plug-in of an axis (a bias's, a denoiser's, a resolve's: plugin_axis.h's
    // axisParams marks them): while another plug-in is chosen (its `needs` unmet) it is left out of
    // the values, so raster.json and metrics.json list only the chosen plug-in's parameters.
    bool pluginParam = false;
    // Its former name, still accepted with a deprecation notice (renamedFrom).
    std::optional<FormerName> former = {};
    // A method parameter whose values are named designs (pattern=three, contact_method=bevy):
    // each name's provenance, parallel to `names`, so a row that picks one says whose design it
    // grades (provenance.h). Empty where the values are the technique's own choices.
    std::vector<Provenance> provenances = {};
    // A method parameter's former value names, still accepted with a deprecation notice.
    std::vector<FormerValue> formerValues = {};
};
using ParamTable = std::vector<ParamSpec>;

// A parameter that picks one of `names`: value k is names[k], the default names[defaultIndex].
ParamSpec methodParam(std::string name, int defaultIndex, std::vector<std::string> names,
                      std::string doc);
// `spec`, which was called `former.name` before.
ParamSpec renamedFrom(ParamSpec spec, FormerName former);
// The name of value v of a method parameter, or its number ("2048", "0.5") for any other.
std::string paramValueText(const ParamSpec& spec, double v);

// A setting that meets spec.needs: its first alternative ("denoiser=svgf" of
// "denoiser=svgf|ffx"); empty when it needs none.
std::string neededSetting(const ParamSpec& spec);
// Every setting spec needs along its chain (ParamSpec::needs), each need's first alternative, the
// outermost first: {"contact=on", "contact_method=bevy"} for contact_steps.
std::vector<std::string> neededSettings(const ParamSpec& spec, const ParamTable& table);

// The table's quality parameter, or null.
const ParamSpec* qualityParam(const ParamTable& table);

// One parameter's value, with whether the table declares it an integer (JSON writes 2048, not
// 2048.0).
struct ParamSetting {
    double value = 0.0;
    bool integer = false;
};

// Validated values: every parameter of the table, defaults filled in. Only `parseParams` makes
// one, so a technique's constructor reads values that are known to be in range.
class ParamValues {
  public:
    double real(const std::string& name) const;  // not in the table: std::invalid_argument
    int integer(const std::string& name) const;
    const std::map<std::string, double>& all() const { return values_; }
    std::map<std::string, ParamSetting> settings() const;
    // Whether the setting named the parameter (else it holds its default): for a parameter that
    // means nothing unless another is on, which is then an error rather than silently ignored.
    bool given(const std::string& name) const { return given_.count(name) > 0; }
    // One notice per former name the setting used ("technique raytraced: `alpha` is deprecated,
    // use `history` (history = 1 - alpha); accepted until format 8"), for the caller to say once:
    // on stderr (the CLI), as a warning (compare's callbacks, the API's warnings).
    const std::vector<std::string>& deprecations() const { return deprecations_; }

  private:
    friend ParamValues parseParams(const std::string&, const ParamTable&,
                                   const std::vector<std::string>&);
    std::map<std::string, double> values_;
    std::map<std::string, bool> integer_;
    std::set<std::string> given_;
    std::vector<std::string> deprecations_;
};

// Whether the values meet spec.needs ("key=a|b": any of them) and, in turn, what that key's own
// spec needs (contact_steps needs contact_method=bevy|guarded, which needs contact=on); true for a
// spec that needs none.
bool needsMet(const ParamSpec& spec, const ParamTable& table, const ParamValues& values);

// Parses "key=value" settings against the table; unknown keys, non-numbers, non-integers and
// values out of range are InputErrors naming the technique, the key and what is valid. A key that
// is a parameter's former name sets that parameter (converted) and adds a deprecation notice;
// giving both names is an InputError.
ParamValues parseParams(const std::string& technique, const ParamTable& table,
                        const std::vector<std::string>& settings);

// A GLSL float literal that keeps the value: "1e-07" and "0.000000" are not the same number.
std::string glslFloat(double v);
// "#define NAME <glslFloat(v)>\n"
std::string glslDefine(const std::string& name, double v);

}  // namespace so
