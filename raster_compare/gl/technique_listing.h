// Every registered technique with its family, summary and parameter table (names, defaults,
// ranges, meaning), as text, JSON (`techniques --json`, format_version 5) or the Markdown of
// docs/techniques.md (generated from the tables; a test fails when the document differs).
#pragma once

#include <string>

namespace so {

enum class ListingFormat { Text, Json, Markdown };

// `techniques --json`'s format_version (its --help says it from here).
inline constexpr int kTechniquesJsonFormat = 5;

std::string techniquesListing(ListingFormat format);

}  // namespace so
