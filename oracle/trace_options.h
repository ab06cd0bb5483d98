// The trace option table's values (core/trace_option_table.h) written into the oracle's options:
// what the command line, the API and the sweep spec each give, checked by the table and applied
// by one function, so that every surface means the same by a key.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/trace_option_table.h"
#include "oracle/oracle.h"

namespace so {

// Checks each of `values` (naming its field as `naming` says) and writes it into `o`; a 0 that
// `naming` allows for an unset option leaves o's default.
void applyTraceOptions(const TraceOptionValues& values, const TraceOptionNaming& naming,
                       OracleOptions& o);

// The table's defaults written into OracleOptions{} (TraceOptionTable.OracleDefaultsAreTheTables
// compares the two).
OracleOptions tableDefaultOracleOptions();

// The value of option `key` in `o`, as the table's row states it; the image size is `cam`'s (the
// scene camera's where `o` leaves it 0).
TraceOptionValue traceOptionValueOf(const OracleOptions& o, const CameraDesc& cam,
                                    const std::string& key);

// Every row that changes the oracle's result (OptionSpec::changesResult) with its value in `o`, by
// key: where the oracle cache's key (oracle_cache.h) and a tile's "options" start, so that an
// option added to the table is in both without another edit.
nlohmann::json resultOptionsJson(const OracleOptions& o, const CameraDesc& cam);

// The keys applyTraceOptions can write, in its order (a test compares them with the table's).
std::vector<std::string> appliedTraceOptionKeys();

}  // namespace so
