#include "analysis/csv.hpp"
#include "core/output_file.hpp"
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace terrace::analysis {

int CsvTable::find(const std::string& name) const {
    for (std::size_t c = 0; c < header.size(); ++c)
        if (header[c] == name) return static_cast<int>(c);
    return -1;
}

namespace {

std::vector<std::string> splitFields(const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream in(line);
    std::string field;
    while (std::getline(in, field, ',')) {
        const auto first = field.find_first_not_of(" \t\r");
        const auto last = field.find_last_not_of(" \t\r");
        fields.push_back(first == std::string::npos ? "" : field.substr(first, last - first + 1));
    }
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    return fields;
}

double parseNumber(const std::string& field, const std::filesystem::path& path, int line) {
    if (field == "nan" || field == "NaN" || field == "-nan")
        return std::numeric_limits<double>::quiet_NaN();
    double value = 0.0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (ec != std::errc() || end != field.data() + field.size())
        throw CsvError(path.string() + ":" + std::to_string(line) + ": not a number: '" + field +
                       "'");
    return value;
}

} // namespace

void writeCsv(const std::filesystem::path& path, const CsvTable& table) {
    for (const auto& column : table.columns)
        if (static_cast<int>(column.size()) != table.rows())
            throw CsvError(path.string() + ": columns of unequal length");
    if (table.columns.size() != table.header.size())
        throw CsvError(path.string() + ": one header name per column");
    std::ostringstream out;
    out.precision(17);
    for (std::size_t c = 0; c < table.header.size(); ++c)
        out << (c ? "," : "") << table.header[c];
    out << '\n';
    for (int r = 0; r < table.rows(); ++r) {
        for (std::size_t c = 0; c < table.columns.size(); ++c) {
            const double v = table.columns[c][r];
            out << (c ? "," : "");
            if (std::isfinite(v))
                out << v;
            else
                out << "nan";
        }
        out << '\n';
    }
    writeFileAtomically(path, out.str()); // IoError naming the file and the cause
}

CsvTable readCsv(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw CsvError("cannot read " + path.string());
    CsvTable table;
    std::string line;
    int lineNumber = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos) continue;
        // Comment lines (thermo.csv's units and notes under its header) carry no data.
        if (line[first] == '#') continue;
        const auto fields = splitFields(line);
        if (table.header.empty()) {
            table.header = fields;
            table.columns.assign(fields.size(), {});
            continue;
        }
        if (fields.size() != table.header.size())
            throw CsvError(path.string() + ":" + std::to_string(lineNumber) + ": " +
                           std::to_string(fields.size()) + " fields, header has " +
                           std::to_string(table.header.size()));
        for (std::size_t c = 0; c < fields.size(); ++c)
            table.columns[c].push_back(parseNumber(fields[c], path, lineNumber));
    }
    if (table.header.empty()) throw CsvError(path.string() + ": empty file, no header");
    return table;
}

} // namespace terrace::analysis
