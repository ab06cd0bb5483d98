#include "cli/compare_command.h"

#include <iostream>

#include "cli/output.h"
#include "core/error.h"

namespace so {

ImageSpec parseImageSpec(const std::string& text) {
    const auto eq = text.find('=');
    const std::string label = text.substr(0, std::min(eq, text.size()));
    const std::string path = eq == std::string::npos ? "" : text.substr(eq + 1);
    if (label.empty() || path.empty())
        throwInputError("command line", "--image",
                        "\"" + printable(text, 60) + "\" is not LABEL=PATH");
    return makeImageSpec(label, path);
}

namespace {

int verifyExitCode(const CompareOptions& options, const OracleStats& stats) {
    if (!stats.verified()) return 0;
    const uint64_t bad = stats.disagreements();
    std::cout << "  oracle verified: " << bad << " disagreements\n";
    if (!bad) return 0;
    std::cerr << "error: " << options.scenePath << ": verify: " << bad
              << " pixels where the oracle disagrees with the exact re-trace (metrics.json "
                 "oracle.stats.verify)\n";
    return 3;
}

}  // namespace

CompareCallbacks printingCallbacks(bool progress) {
    CompareCallbacks c;
    c.warning = [](const std::string& w) { std::cerr << "warning: " << w << "\n"; };
    if (!progress) return c;
    // The camera path's frames, a line each as they are done; the techniques' own progress is the
    // "rendering" lines below.
    c.progress = [](const ProgressUpdate& u) {
        if (u.stage == "camera path frames")
            std::cerr << "camera path: frame " << u.done << " of " << u.total << "\n";
        if (u.stage == "sequence frames")
            std::cerr << "sequence: frame " << u.done << " of " << u.total << "\n";
        if (u.stage == "converge frames")
            std::cerr << "converge: frame " << u.done << " of " << u.total << "\n";
        return true;
    };
    c.renderingGroup = [](const std::vector<std::string>& labels) {
        std::cerr << "rendering";
        for (size_t i = 0; i < labels.size(); ++i) std::cerr << (i ? ", " : " ") << labels[i];
        std::cerr << (labels.size() > 1 ? " (frames interleaved)" : "") << "\n";
    };
    return c;
}

int printCompareSummary(const CompareOptions& options, const CompareRun& run,
                        const CompareOutputFiles& files) {
    std::cout << "compared " << options.scenePath << ": " << options.techniques.size()
              << " techniques, " << options.images.size() << " images, oracle "
              << (run.atPoints           ? "at the G-buffer's points"
                  : run.oracle.fromCache ? "from the cache"
                                         : "traced")
              << "\n  " << files.metricsJson.string() << "\n  " << files.metricsCsv.string()
              << "\n  " << files.metricsWideCsv.string() << "\n";
    return verifyExitCode(options, run.oracle.stats);
}

// The command's errors name its flags.
const CompareOptionNames kCompareFlags = {
    "command line", "--technique",          "--image", "--points",   "--frames-path",
    "--verify",     "--width and --height", "--out",   "--sequence", "--converge"};

int runCompareCommand(CompareOptions options, bool progress) {
    options.names = kCompareFlags;
    CompareRun run = compareScene(options, printingCallbacks(progress));
    return printCompareSummary(options, run, writeCompareRun(options, run));
}

}  // namespace so
