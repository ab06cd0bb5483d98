#include "cli/sweep_merge.h"

#include <iostream>

#include "cli/output.h"
#include "raster_compare/pipeline/sweep_merge.h"

namespace so {

int runSweepMerge(const SweepMergeOptions& options) {
    const std::filesystem::path dir = options.dir;
    const SweepMerge merge = mergeSweep(dir, options.imagesChecked);
    printWarnings(merge.warnings);
    std::cout << "merged " << merge.finished << " of " << merge.tasks << " tasks of " << merge.name
              << "\n  " << merge.metricsCsv.string() << "\n  " << merge.metricsWideCsv.string()
              << "\n  " << merge.metricsJson.string() << "\n  " << merge.report.string() << "\n";
    if (merge.failed.empty()) return 0;
    std::cerr << merge.failed.size() << " of " << merge.tasks << " tasks did not finish"
              << (options.quiet ? "\n" : ":\n");
    for (size_t i = 0; i < merge.failed.size() && !options.quiet; ++i) {
        const SweepFailure& f = merge.failed[i];
        std::cerr << "  " << f.task << " " << f.label << " on " << f.scene << ": " << f.reason
                  << (f.log.empty() ? "" : " (" + (dir / f.log).string() + ")") << "\n";
    }
    std::cerr << "rerunning the same `shadow-oracle sweep` runs only those\n";
    return 1;
}

}  // namespace so
