#include "lab/csv_writer.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

namespace foresight::lab {

std::string csv_cell(const std::string& cell) {
  if (cell.find_first_of(",\"\r\n") == std::string::npos) return cell;
  std::string out = "\"";
  for (char c : cell) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string csv_text(const CsvTable& table) {
  std::string out;
  auto line = [&out](const std::vector<std::string>& cells) {
    for (size_t i = 0; i < cells.size(); ++i) {
      if (i > 0) out += ',';
      out += csv_cell(cells[i]);
    }
    out += '\n';
  };
  line(table.header);
  for (const auto& row : table.rows) line(row);
  return out;
}

bool csv_write(const std::filesystem::path& path, const CsvTable& table, std::string& error) {
  std::ofstream out(path, std::ios::binary);
  const std::string text = csv_text(table);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) {
    error = path.string() + ": cannot write";
    return false;
  }
  return true;
}

std::string format_number(double value, int decimals) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

}  // namespace foresight::lab
