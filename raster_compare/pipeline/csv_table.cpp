#include "raster_compare/pipeline/csv_table.h"

#include <fstream>
#include <sstream>

#include "core/error.h"

namespace so {

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

void WideCsv::add(const std::vector<std::pair<std::string, std::string>>& row) {
    std::map<std::string, std::string> r;
    for (const auto& [column, value] : row) {
        if (!r.count(column) && !known_.count(column)) {
            known_.insert(column);
            columns_.push_back(column);
        }
        r[column] = value;
    }
    rows_.push_back(std::move(r));
}

std::string WideCsv::text() const {
    std::ostringstream out;
    for (size_t c = 0; c < columns_.size(); ++c) out << (c ? "," : "") << csvField(columns_[c]);
    out << "\n";
    for (const auto& r : rows_) {
        for (size_t c = 0; c < columns_.size(); ++c) {
            const auto it = r.find(columns_[c]);
            out << (c ? "," : "") << (it == r.end() ? "" : csvField(it->second));
        }
        out << "\n";
    }
    return out.str();
}

void WideCsv::write(const std::filesystem::path& path) const {
    std::ofstream out(path, std::ios::binary);
    out << text();
    if (!out) throwInputError(path.string(), "", "cannot be written");
}

}  // namespace so
