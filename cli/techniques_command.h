// `shadow-oracle techniques`: every registered technique with its family, summary and parameter
// table (names, defaults, ranges, meaning), as text, JSON or the Markdown of docs/techniques.md
// (generated from the tables; a test fails when the document differs).
#pragma once

#include <string>

namespace so {

enum class ListingFormat { Text, Json, Markdown };

std::string techniquesListing(ListingFormat format);

int runTechniquesCommand(ListingFormat format);

}  // namespace so
