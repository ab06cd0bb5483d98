// Provenance at the command line (issue 63, label gl): compare writes each technique row's
// provenance into metrics.json, and the report marks the rows that grade a variant or a design of
// our own, and only those.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "gl_test_context.h"

namespace so {
namespace {

using namespace so::test;
namespace fs = std::filesystem;

TEST(ProvenanceCli, MetricsCarryItAndTheReportMarksWhatIsNotFaithful) {
    REQUIRE_GL();
    const std::string scene = std::string(SO_SCENES_DIR) + "/contact_box.scene.json";
    const fs::path dir =
        fs::temp_directory_path() / ("so_provenance_" + std::to_string(::getpid()));
    const std::string cmd = std::string(SO_CLI_PATH) + " compare " + scene + " --out " +
                            dir.string() +
                            " --technique planar --technique pcss --technique basic:bias=slope"
                            " --width 32 --height 24 --frames 1 --warmup 0 > /dev/null 2>&1";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
    std::ifstream in(dir / "metrics.json");
    const nlohmann::json results = nlohmann::json::parse(in)["results"];
    ASSERT_EQ(results.size(), 3u);
    std::map<std::string, nlohmann::json> byLabel;
    for (const nlohmann::json& r : results) byLabel[r["label"]] = r["provenance"];
    // planar is Blinn's as published; pcss a listed variant of Fernando's; basic with the slope
    // bias has two parts, the technique's and the bias's.
    EXPECT_EQ(byLabel["planar"]["fidelity"], "faithful");
    EXPECT_EQ(byLabel["pcss"]["parts"][0]["of"], "technique pcss");
    EXPECT_EQ(byLabel["pcss"]["parts"][0]["fidelity"], "variant");
    EXPECT_NE(byLabel["pcss"]["fidelity"], "faithful");
    EXPECT_FALSE(byLabel["pcss"]["parts"][0]["deviations"].empty());
    const nlohmann::json& slope = byLabel["basic:bias=slope"]["parts"];
    ASSERT_EQ(slope.size(), 2u);
    EXPECT_EQ(slope[1]["of"], "bias=slope");

    std::ifstream page(dir / "report.html");
    const std::string html(std::istreambuf_iterator<char>(page), {});
    // Every row that is not faithful is marked after its label, in the tables and the images;
    // a faithful row (planar) nowhere.
    size_t notFaithful = 0;
    for (const auto& [label, provenance] : byLabel) {
        const bool faithful = provenance["fidelity"] == "faithful";
        notFaithful += faithful ? 0 : 1;
        const std::string mark = " <sup class=\"fidelity\" data-fidelity=\"" +
                                 provenance["fidelity"].get<std::string>() + "\"";
        const bool inTable = html.find(">" + label + "</a>" + mark) != std::string::npos;
        const bool inImages = html.find("<b>" + label + "</b>" + mark) != std::string::npos;
        EXPECT_EQ(inTable, !faithful) << label;
        EXPECT_EQ(inImages, !faithful) << label;
        EXPECT_EQ(html.find(">" + label + "</a> <sup"),
                  faithful ? std::string::npos : html.find(">" + label + "</a>" + mark))
            << label;
    }
    EXPECT_GE(notFaithful, 1u);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace so
