// Every registered technique with its family, summary, provenance (provenance.h) and parameter
// table (names, defaults, ranges, meaning), and every axis of plug-ins (plugin_axis.h: the
// ray-tracing family's denoisers) with each plug-in's summary and table, as text, JSON (`techniques
// --json`, format_version 7) or the Markdown of docs/techniques.md (generated from the tables; a
// test fails when the document differs).
#pragma once

#include <string>
#include <vector>

#include "raster_compare/gl/plugin_axis.h"

namespace so {

enum class ListingFormat { Text, Json, Markdown };

// `techniques --json`'s format_version (its --help says it from here).
// 6 (issue 62): "axes", and `former` on a renamed parameter.
// 7 (issue 63): `provenance` ({anchor, fidelity, deviations}) on every technique and plug-in, and
// `provenances` (one per name) on a method parameter whose values are named designs. Issue 64
// added the `resolve` axis to "axes" within format 7 (an entry added, none changed).
inline constexpr int kTechniquesJsonFormat = 7;

// Every axis of plug-ins the registered families have (the denoisers), in the order listed.
std::vector<PluginAxis> registeredAxes();

// The registered techniques and `axes`.
std::string techniquesListing(ListingFormat format,
                              const std::vector<PluginAxis>& axes = registeredAxes());

}  // namespace so
