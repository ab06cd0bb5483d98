// CSV as compare and sweep-merge write it (docs/cli.md, docs/sweep.md): RFC 4180 quoting, and the
// wide table whose columns are the union of its rows' columns.
#pragma once

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace so {

// The field quoted when it holds a comma, a quote or a line break.
std::string csvField(const std::string& s);

// One row per light x setting, the setting's parameters ("param.NAME") and every metric as
// columns. Columns are the union over rows, in first-seen order; a row without one leaves it empty.
class WideCsv {
  public:
    void add(const std::vector<std::pair<std::string, std::string>>& row);
    // As text, or into a file (an InputError naming it when it cannot be written).
    std::string text() const;
    void write(const std::filesystem::path& path) const;

  private:
    std::vector<std::string> columns_;
    std::set<std::string> known_;
    std::vector<std::map<std::string, std::string>> rows_;
};

}  // namespace so
