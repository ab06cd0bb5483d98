#include "cli/metrics_command.h"

#include <algorithm>
#include <iostream>
#include <sstream>

#include "raster_compare/compare/metric_table.h"

namespace so {

namespace {

// One metric a line, the name padded so that the units line up.
std::string text() {
    size_t width = 0;
    for (const MetricInfo& m : allMetrics()) width = std::max(width, std::string(m.name).size());
    std::ostringstream o;
    for (const MetricInfo& m : allMetrics())
        o << m.name << std::string(width + 2 - std::string(m.name).size(), ' ') << "["
          << unitName(m.unit) << "; better: " << betterName(m.better)
          << "; where: " << scopeName(m.scope) << "]  " << m.description << "\n";
    return o.str();
}

}  // namespace

std::string metricsListing(bool markdown) {
    return markdown ? metricTableMarkdown() : text();
}

int runMetricsCommand(bool markdown) {
    std::cout << metricsListing(markdown);
    return 0;
}

}  // namespace so
