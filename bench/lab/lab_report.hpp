#pragma once
// Turning a LabResult into what people read: text tables, CSV tables, SVG figures, one JSON line.
#include "lab/csv_writer.hpp"
#include "lab/lab_experiments.hpp"

#include <filesystem>
#include <string>

namespace foresight::lab {

/// Fig. 9 tables (paper rate and today's rate), the spare-time model and the shape checks.
std::string fig9_text(const Fig9Result& fig9);
/// Per tree-size table: one row per (model, strategy, interval).
CsvTable fig9_csv(const Fig9Result& fig9);
std::string fig9_svg(const Fig9Result& fig9, const std::string& scene);

/// One row per node end position per strategy.
CsvTable fig10_csv(const Fig10Result& fig10);
std::string fig10_text(const Fig10Result& fig10);
std::string fig10_svg(const Fig10Result& fig10, const Scene& scene);

std::string navigation_text(const NavigationResult& navigation);
/// Rows of every result given (replay and closed loop), with a "mode" column.
CsvTable navigation_csv(const std::vector<const NavigationResult*>& results);
/// One row per followed command change of every run: when, how long, which segments.
CsvTable responses_csv(const std::vector<const NavigationResult*>& results);

/// Every figure, then where it ran (bench::json_line), as one JSON object on one line (no trailing newline).
std::string lab_json(const LabResult& result);

/// Writes fig9.csv, fig9.svg, fig10.csv, fig10.svg, navigation.csv and responses.csv into `dir` (created).
/// False with a reason on an I/O error.
bool lab_write_files(const LabResult& result, const Scene& scene, const std::filesystem::path& dir,
                     std::string& error);

}  // namespace foresight::lab
