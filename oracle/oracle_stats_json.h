// What oracle.json's writer (oracle_stats.cpp) and its reader (oracle_stats_reader.cpp) must agree
// on beyond the field tables (pass_stats.h): the verify tests' texts and which of the exact pass's
// counters a light's JSON holds. Internal to the oracle's library.
#pragma once

#include <cstring>

#include "oracle/pass_stats.h"

namespace so::oracle_stats_json {

// The verify tests' texts: written, and read back to tell a sampled light's verification.
inline constexpr const char* kAreaTest =
    "area: |V - V_ref| <= z * combined stderr (+ bound where NAME.bound bounds V)";
inline constexpr const char* kHardTest = "hard: exact re-trace, V must match";

inline bool isDisagreementKey(const char* key) {
    return std::strncmp(key, "disagreement.", 13) == 0;
}

inline bool isBoundKey(const char* key) {
    return std::strncmp(key, "bound.", 6) == 0;
}

// The exact pass's counters a light's JSON holds: disagreement with both, bound for bounded lights.
inline bool keepsExactKey(const ExactPenumbraStats& e, const char* key) {
    if (isDisagreementKey(key)) return e.method == PenumbraMethod::Both;
    if (isBoundKey(key)) return e.errorKind == "bound";
    return true;
}

}  // namespace so::oracle_stats_json
