// A sweep folder for the pipeline's tests: a plan of two scenes x two settings of a made-up
// technique, written as `shadow-oracle sweep` writes it (sweep.json, tasks.jsonl), without GL.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "raster_compare/pipeline/sweep_spec.h"

namespace so::test {

// "shadow" with one parameter, alpha in [0, 16]; anything else is refused as compare would.
inline ParamNumbers validateShadow(const std::string& technique,
                                   const std::vector<std::string>& settings) {
    if (technique != "shadow") throwInputError("technique", technique, "unknown technique");
    ParamNumbers numbers;
    for (const std::string& kv : settings) {
        const std::string key = kv.substr(0, kv.find('='));
        if (key != "alpha") throwInputError(technique, key, "unknown parameter");
        numbers[key] = std::stod(kv.substr(kv.find('=') + 1));
    }
    return numbers;
}

class SweepFolder {
  public:
    explicit SweepFolder(const std::string& name)
        : root_(std::filesystem::temp_directory_path() /
                ("so_" + name + "_" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(root_);
        std::filesystem::create_directories(root_ / "scenes");
        for (const char* s : {"a.scene.json", "b.scene.json"})
            std::ofstream(root_ / "scenes" / s) << "{}";
        plan_ = planSweepText(R"({"sweep_format": 1, "name": "pipe test",
            "scenes": ["scenes/*.scene.json"],
            "techniques": [{"name": "shadow", "params": {"alpha": [1, 2]}}]})",
                              root_ / "spec.json", validateShadow);
        std::filesystem::create_directories(dir());
        writePlan(dir(), plan_);
    }
    ~SweepFolder() { std::filesystem::remove_all(root_); }
    SweepFolder(const SweepFolder&) = delete;
    SweepFolder& operator=(const SweepFolder&) = delete;

    std::filesystem::path dir() const { return root_ / "out"; }
    const SweepPlan& plan() const { return plan_; }

  private:
    std::filesystem::path root_;
    SweepPlan plan_;
};

}  // namespace so::test
