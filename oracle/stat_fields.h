// The counters of the oracle's statistics, listed once per struct: a struct's `fields()` table
// gives each counter's key in oracle.json, its member and how two parts of one run combine (the
// threads of a pass, the bands of `trace --tile`). The threads' reduction, trace-merge and
// oracle.json's writer and reader all walk the table (oracle_stats.cpp), so a new counter is one
// member and one row, and none of them can forget it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <variant>

namespace so {

// How the values of two parts of one run make the whole run's value.
enum class Combine : uint8_t { Sum, Max };

template <class S>
struct StatField {
    // The key in the struct's JSON object; a '.' nests ("rays_skipped.background").
    const char* key;
    // An optional counter is written only where the run has it (e.g. spot lights' outside_cone).
    std::variant<uint64_t S::*, double S::*, std::optional<uint64_t> S::*> member;
    Combine combine = Combine::Sum;
};

namespace stat_fields_detail {
template <class T>
T combined(T a, T b, Combine c) {
    return c == Combine::Sum ? a + b : std::max(a, b);
}
inline void combineInto(uint64_t& total, uint64_t v, Combine c) {
    total = combined(total, v, c);
}
inline void combineInto(double& total, double v, Combine c) {
    total = combined(total, v, c);
}
// Present in the whole where present in any part.
inline void combineInto(std::optional<uint64_t>& total, const std::optional<uint64_t>& v,
                        Combine c) {
    if (v) total = combined(total.value_or(0), *v, c);
}
}  // namespace stat_fields_detail

// Adds part `s` of a run to `total`, field by field as the table says.
template <class S>
void combineStats(S& total, const S& s) {
    for (const StatField<S>& f : S::fields())
        std::visit([&](auto m) { stat_fields_detail::combineInto(total.*m, s.*m, f.combine); },
                   f.member);
}

}  // namespace so
