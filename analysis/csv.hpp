#pragma once
// Correlation data as CSV: one header line of column names, then rows of numbers, comma
// separated, no quoting (the project writes only numbers). Non-finite values are written "nan"
// and read back as NaN, so that a missing error bar never turns into a silent zero.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace terrace::analysis {

class CsvError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct CsvTable {
    std::vector<std::string> header;
    std::vector<std::vector<double>> columns; // columns[c][row]

    int rows() const { return columns.empty() ? 0 : static_cast<int>(columns.front().size()); }
    /// Index of the named column, or −1.
    int find(const std::string& name) const;
};

/// Writes the table (17 significant digits: values survive a round trip exactly), whole or not at
/// all (core/output_file.hpp); a failed write is an IoError naming the file and the cause.
void writeCsv(const std::filesystem::path& path, const CsvTable& table);

/// Reads a table written as above; throws CsvError naming the file and line on anything else.
CsvTable readCsv(const std::filesystem::path& path);

} // namespace terrace::analysis
