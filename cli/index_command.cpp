#include "cli/index_command.h"

#include <iostream>

#include "core/error.h"
#include "raster_compare/compare/index_page.h"

namespace so {

namespace fs = std::filesystem;

namespace {

// Absolute, without "..", "." or a trailing "/", so that parents and relative links come out
// the same however the folder was spelled on the command line.
fs::path normalFolder(const std::string& dir) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(fs::absolute(dir), ec);
    if (ec) throwInputError(dir, "", "cannot be resolved: " + ec.message());
    return p;
}

// The folder must be a compare output: a wrong argument is named before anything is written.
fs::path metricsFileOf(const std::string& dir) {
    if (!fs::is_directory(dir)) throwInputError(dir, "", "no such folder");
    const fs::path metrics = fs::path(dir) / "metrics.json";
    if (!fs::is_regular_file(metrics))
        throwInputError(dir, "", "no metrics.json here (not an output folder of compare)");
    return metrics;
}

// The link from the page's folder to the run's report, with '/' on every platform.
std::string reportHref(const std::string& dir, const fs::path& pageDir) {
    const fs::path report = normalFolder(dir) / "report.html";
    if (!fs::is_regular_file(report))
        std::cerr << "warning: " << dir << ": no report.html; its links will not open\n";
    return fs::relative(report, pageDir).generic_string();
}

}  // namespace

fs::path defaultIndexPath(const std::vector<std::string>& dirs) {
    const fs::path first = normalFolder(dirs.at(0)).parent_path();
    fs::path common = first;
    for (size_t i = 1; i < dirs.size(); ++i) {
        const fs::path parent = normalFolder(dirs[i]).parent_path();
        fs::path shared;
        for (auto a = common.begin(), b = parent.begin();
             a != common.end() && b != parent.end() && *a == *b; ++a, ++b)
            shared /= *a;
        common = shared;
    }
    return (common.empty() ? first : common) / "index.html";
}

int runIndexCommand(const IndexOptions& options) {
    std::vector<fs::path> metricsFiles;
    for (const std::string& dir : options.dirs) metricsFiles.push_back(metricsFileOf(dir));
    const fs::path out =
        options.outPath.empty() ? defaultIndexPath(options.dirs) : fs::path(options.outPath);
    const fs::path pageDir = normalFolder(fs::absolute(out).parent_path().string());
    std::error_code ec;
    fs::create_directories(pageDir, ec);
    if (ec) throwInputError(out.string(), "--out", "cannot create its folder: " + ec.message());
    std::vector<IndexEntry> entries;
    for (size_t i = 0; i < options.dirs.size(); ++i)
        entries.push_back(
            {readSceneMetrics(metricsFiles[i].string()), reportHref(options.dirs[i], pageDir)});
    writeIndexPage(out.string(), entries);
    std::cout << out.string() << "\n";
    return 0;
}

}  // namespace so
