#include "core/tool_info.h"

#include "core/version.h"

namespace so {

nlohmann::json toolJson() {
    return {{"name", "shadow-oracle"}, {"version", kToolVersion}, {"git_revision", kGitRevision}};
}

std::string toolVersionString() {
    return std::string(kToolVersion) + " " + kGitRevision;
}

}  // namespace so
