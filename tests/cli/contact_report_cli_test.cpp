// The report's contact section end to end (label gl): `compare` on the contact box with a shadow
// map both with contact=on and with contact=off at otherwise equal settings shows, for the light,
// the peter-panning the march closes (positive) and no more acne; a run without such a pair has
// no section (docs/report.md, "Contact shadows").
#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "cli_run.h"
#include "gl_test_context.h"

namespace so::test {
namespace {

namespace fs = std::filesystem;

// The attribute `name` of the contact table's row for `on`, as a number; NaN when absent.
double rowValue(const std::string& page, const std::string& on, const std::string& name) {
    const size_t row = page.find("<tr data-on=\"" + on + "\"");
    if (row == std::string::npos) return std::nan("");
    const size_t a = page.find(name + "=\"", row);
    if (a == std::string::npos || a > page.find('>', row)) return std::nan("");
    return std::stod(page.substr(a + name.size() + 2));
}

std::string compareReport(const fs::path& dir, const std::string& techniques) {
    const RunResult r =
        run("compare " + std::string(SO_SCENES_DIR) +
            "/contact_box.scene.json --width 96 --height 72 --frames 1 --no-cache --quiet --out " +
            dir.string() + " " + techniques);
    EXPECT_EQ(r.exitCode, 0) << r.stdoutText << r.stderrText;
    return readBytes(dir / "report.html");
}

TEST(ContactReport, PairedSettingsGetTheSectionWithItsSigns) {
    REQUIRE_GL();
    const fs::path dir =
        fs::temp_directory_path() / ("so_contact_report_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    // A coarse map with 4 texels of minimum bias: a gap at the box's foot for the march to close
    // (the default 2048 map's bias leaves none at this size).
    const std::string map = "pcf:resolution=256,min=4";
    const std::string page =
        compareReport(dir / "paired", "--technique " + map + " --technique " + map +
                                          ",contact=on --technique slope-bias");
    EXPECT_NE(page.find("<h3>Contact shadows</h3>"), std::string::npos);
    const std::string on = map + ",contact=on";
    EXPECT_GT(rowValue(page, on, "data-peter-panning-closed"), 0.0);
    EXPECT_LE(rowValue(page, on, "data-acne-added"), 0.01);  // issue 54's bar
    EXPECT_GE(rowValue(page, on, "data-screen-bleed-added"), 0.0);
    // Each row's parameters name a method's value by its name, as the setting was written.
    EXPECT_NE(page.find(" contact=on contact_bilinear_threshold=0.02 "), std::string::npos);
    EXPECT_NE(page.find(" contact=off contact_bilinear_threshold=0.02 "), std::string::npos);
    EXPECT_NE(page.find(" contact_method=bevy "), std::string::npos);
    // slope-bias has no contact=on partner, so only the one row.
    EXPECT_EQ(page.find("<tr data-on=", page.find("<tr data-on=") + 1), std::string::npos);

    const std::string unpaired = compareReport(
        dir / "unpaired", "--technique " + map + " --technique slope-bias:contact=on");
    EXPECT_EQ(unpaired.find("Contact shadows"), std::string::npos);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace so::test
