// compare's and sweep-merge's CSV (raster_compare/pipeline/csv_table.h): RFC 4180 quoting, and the
// wide table whose columns are the union of its rows'. Label "pipeline".
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "raster_compare/pipeline/csv_table.h"

namespace so {
namespace {

TEST(CsvTable, FieldsAreQuotedOnlyWhenTheyMustBe) {
    EXPECT_EQ(csvField("pcf"), "pcf");
    EXPECT_EQ(csvField(""), "");
    EXPECT_EQ(csvField("pcf:kernel=3,resolution=2048"), "\"pcf:kernel=3,resolution=2048\"");
    EXPECT_EQ(csvField("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csvField("two\nlines"), "\"two\nlines\"");
    EXPECT_EQ(csvField("cr\rhere"), "\"cr\rhere\"");
}

TEST(CsvTable, WideColumnsAreTheUnionInFirstSeenOrder) {
    WideCsv t;
    t.add({{"light", "sun"}, {"mae", "0.5"}});
    t.add({{"light", "lamp,left"}, {"param.k", "2"}, {"mae", "0.25"}});
    t.add({{"rmse", "1"}});
    EXPECT_EQ(t.text(),
              "light,mae,param.k,rmse\n"
              "sun,0.5,,\n"
              "\"lamp,left\",0.25,2,\n"
              ",,,1\n");
}

TEST(CsvTable, AnUnwritableFileIsAnInputErrorNamingIt) {
    WideCsv t;
    t.add({{"a", "1"}});
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "so_csv_table_test_no_such_folder";
    std::filesystem::remove_all(dir);
    try {
        t.write(dir / "metrics_wide.csv");
        FAIL() << "wrote into a folder that does not exist";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("metrics_wide.csv"), std::string::npos) << e.what();
    }
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / "so_csv_table_test.csv";
    t.write(file);
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), "a\n1\n");
    std::filesystem::remove(file);
}

}  // namespace
}  // namespace so
