// What the sweep tests share: running the CLI, writing a spec, and a sweep's merged results with
// the timings left out (they differ from run to run; everything else must not).
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_run.h"

namespace so::test {

// Runs `shadow-oracle ARGS`; its standard output, then its error, into *output; the exit code.
inline int runCli(const std::string& args, std::string* output) {
    const RunResult r = run(args);
    *output = r.stdoutText + r.stderrText;
    return r.exitCode;
}

// A metric that measures time (or says whether a time was noisy): not comparable between runs.
inline bool isTiming(const std::string& key) {
    return key.find("_ms") != std::string::npos || key.find("seconds") != std::string::npos ||
           key.find("noisy") != std::string::npos || key == "timings";
}

inline nlohmann::json withoutTimings(const nlohmann::json& j) {
    if (!j.is_object()) return j;
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [k, v] : j.items())
        if (!isTiming(k)) out[k] = withoutTimings(v);
    return out;
}

// The merged metrics.json of a sweep folder: task id -> its result, timings left out.
inline std::map<std::string, nlohmann::json> mergedResults(const std::filesystem::path& dir) {
    std::ifstream in(dir / "metrics.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    std::map<std::string, nlohmann::json> results;
    for (const nlohmann::json& r : j.at("results")) {
        nlohmann::json kept = withoutTimings(r);
        kept.erase("gl");  // the renderer's name and version: the same machine here anyway
        results[r.at("task").at("id").get<std::string>()] = kept;
    }
    return results;
}

// The fields of one CSV line (RFC 4180 quoting, no line breaks inside fields).
inline std::vector<std::string> csvFields(const std::string& line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
            fields.back() += '"';
            ++i;
        } else if (c == '"') {
            quoted = !quoted;
        } else if (c == ',' && !quoted) {
            fields.emplace_back();
        } else {
            fields.back() += c;
        }
    }
    return fields;
}

// The lines of a merged metrics.csv whose metric (the fifth column) is not a timing, sorted.
inline std::vector<std::string> csvWithoutTimings(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line)) {
        const std::vector<std::string> f = csvFields(line);
        if (f.size() < 6 || isTiming(f[4]) || f[4].rfind("cost.oracle", 0) == 0) continue;
        lines.push_back(line);
    }
    std::sort(lines.begin(), lines.end());
    return lines;
}

}  // namespace so::test
