// `shadow-oracle index DIR... [--out FILE]`: one HTML page over the output folders of several
// compare runs (raster_compare/compare/index_page.h), linking to each run's report.html.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace so {

struct IndexOptions {
    std::vector<std::string> dirs;  // output folders of `compare`, each with metrics.json
    std::string outPath;            // empty: defaultIndexPath(dirs)
};

// index.html in the deepest folder that holds every DIR (the first DIR's parent for one DIR), so
// that the page sits beside the runs it links to.
std::filesystem::path defaultIndexPath(const std::vector<std::string>& dirs);

int runIndexCommand(const IndexOptions& options);

}  // namespace so
