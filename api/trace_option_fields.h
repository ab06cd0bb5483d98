// TraceOptions' fields by the keys of the trace option table (core/trace_option_table.h): what
// the API checks and applies through the table. TraceOptionTable.ApiStructHoldsTheTablesDefaults
// checks that the keys are the table's API rows and that TraceOptions{} holds their defaults.
#pragma once

#include "core/trace_option_table.h"
#include "shadow_oracle/shadow_oracle.h"

namespace shadow_oracle::detail {

inline so::TraceOptionValues traceOptionValues(const TraceOptions& o) {
    const auto n = [](double v) { return so::TraceOptionValue{v, ""}; };
    const auto t = [](const std::string& v) { return so::TraceOptionValue{0.0, v}; };
    return {{"width", n(o.width)},
            {"height", n(o.height)},
            {"threads", n(o.threads)},
            {"seed", n(o.seed)},
            {"target_error", n(o.targetError)},
            {"agreement_target", n(o.agreementTarget)},
            {"max_spp", n(o.maxSpp)},
            {"spp", n(o.fixedSpp)},
            {"verify", n(o.verify)},
            {"penumbra", t(o.penumbra)},
            {"exact_pixels", t(o.exactPixels)},
            {"bound_target", n(o.boundTarget)},
            {"bound_max_sides", n(o.boundMaxSides)}};
}

}  // namespace shadow_oracle::detail
