#include "report_data.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "cli_common.hpp"

namespace lodopt::cli {
namespace {

std::vector<std::string> splitCsvLine(const std::string& line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                fields.back() += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                fields.back() += c;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            fields.emplace_back();
        } else {
            fields.back() += c;
        }
    }
    return fields;
}

}  // namespace

int CsvTable::column(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : int(it - header.begin());
}

const std::string& CsvTable::text(std::size_t row, const std::string& name) const {
    return rows[row][std::size_t(column(name))];
}

double CsvTable::number(std::size_t row, const std::string& name) const {
    const std::string& field = text(row, name);
    if (field.empty()) return NAN;
    try {
        std::size_t used = 0;
        const double value = std::stod(field, &used);
        if (used == field.size()) return value;
    } catch (const std::exception&) {
    }
    // Header is line 1, rows follow without gaps (blank lines are not rows).
    throw UsageError(path + ": row " + std::to_string(row + 1) + ", column '" + name + "': '" + field +
                     "' is not a number");
}

std::vector<double> CsvTable::numbers(const std::string& name) const {
    std::vector<double> values;
    values.reserve(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r) values.push_back(number(r, name));
    return values;
}

CsvTable readCsv(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw UsageError(path + ": cannot be read");
    CsvTable table;
    table.path = path;
    std::string line;
    int lineNumber = 0;
    while (std::getline(file, line)) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        std::vector<std::string> fields = splitCsvLine(line);
        if (table.header.empty()) {
            table.header = std::move(fields);
            continue;
        }
        if (fields.size() != table.header.size()) {
            throw UsageError(path + ": line " + std::to_string(lineNumber) + " has " + std::to_string(fields.size()) +
                             " fields, the header has " + std::to_string(table.header.size()));
        }
        table.rows.push_back(std::move(fields));
    }
    if (table.header.empty()) throw UsageError(path + ": empty file (expected a CSV header line)");
    return table;
}

nlohmann::json readJsonFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw UsageError(path + ": cannot be read");
    std::stringstream text;
    text << file.rdbuf();
    try {
        return nlohmann::json::parse(text.str());
    } catch (const nlohmann::json::exception& error) {
        throw UsageError(path + ": not valid JSON (" + error.what() + ")");
    }
}

double jsonNumber(const nlohmann::json& document, const std::string& key, double fallback) {
    if (!document.is_object()) return fallback;
    const auto it = document.find(key);
    return it != document.end() && it->is_number() ? it->get<double>() : fallback;
}

std::string jsonText(const nlohmann::json& document, const std::string& key, const std::string& fallback) {
    if (!document.is_object()) return fallback;
    const auto it = document.find(key);
    if (it == document.end() || it->is_null()) return fallback;
    if (it->is_string()) return it->get<std::string>();
    return it->dump();
}

Summary summarize(std::vector<double> values) {
    values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
                 values.end());
    Summary summary;
    summary.count = values.size();
    if (values.empty()) {
        summary.median = summary.min = summary.max = NAN;
        return summary;
    }
    std::sort(values.begin(), values.end());
    const std::size_t mid = values.size() / 2;
    summary.median = values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
    summary.min = values.front();
    summary.max = values.back();
    return summary;
}

}  // namespace lodopt::cli
