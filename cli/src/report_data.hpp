// Reading the files other commands wrote, for `lodopt report`: CSV tables and JSON documents,
// with errors that name the file, the line and the column (they come from outside).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lodopt::cli {

// A comma-separated table with a header line. Fields may be double-quoted ("" inside quotes is
// a quote). Empty fields are allowed (a number column reads them as NaN).
struct CsvTable {
    std::string path;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;  // each exactly header.size() fields

    // Index of column `name`, or -1.
    int column(const std::string& name) const;
    bool has(const std::string& name) const { return column(name) >= 0; }
    // The field of `row` in column `name` (which must exist: a caller's check) as a number;
    // NaN when empty. Throws UsageError naming the file, line and column when it is not one.
    double number(std::size_t row, const std::string& name) const;
    const std::string& text(std::size_t row, const std::string& name) const;
    // Every row's value in column `name`.
    std::vector<double> numbers(const std::string& name) const;
};

// Throws UsageError naming the file when it cannot be read, is empty, or a row has the wrong
// number of fields (with its line number).
CsvTable readCsv(const std::string& path);

// Throws UsageError naming the file when it cannot be read or is not JSON.
nlohmann::json readJsonFile(const std::string& path);

// `document[key]` as a number, string, ... or `fallback` when absent or of another type:
// the report shows what a file has and leaves out what it lacks.
double jsonNumber(const nlohmann::json& document, const std::string& key, double fallback);
std::string jsonText(const nlohmann::json& document, const std::string& key, const std::string& fallback = "");

// Median, min and max of finite values (NaN when there is none).
struct Summary {
    double median = 0.0, min = 0.0, max = 0.0;
    std::size_t count = 0;
};
Summary summarize(std::vector<double> values);

}  // namespace lodopt::cli
