#pragma once
// A table written as RFC 4180 CSV: a header row, then rows of already formatted cells.
#include <filesystem>
#include <string>
#include <vector>

namespace foresight::lab {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

/// Quotes a cell when it holds a comma, a quote or a line break.
std::string csv_cell(const std::string& cell);
/// The whole table as CSV text, one line per row, "\n" line ends.
std::string csv_text(const CsvTable& table);
/// Writes csv_text(table) to `path`; false with a reason on an I/O error.
bool csv_write(const std::filesystem::path& path, const CsvTable& table, std::string& error);

/// A number with `decimals` digits after the point ("nan"/"inf" spelled out).
std::string format_number(double value, int decimals);

}  // namespace foresight::lab
