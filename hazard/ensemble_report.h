// The ensemble's report.html (io/output/report_page.h): the member table, the Morris screening,
// the probability and quantile maps and the run-out distribution on one offline page.
#pragma once

#include <string>
#include <vector>

namespace talus::ensemble {

/// Writes DIR/report.html from DIR/members.csv, DIR/morris.csv (when there) and the pictures
/// among `files` (relative to DIR). Throws WriteError.
void writeEnsembleReport(const std::string& dir, const std::vector<std::string>& files);

/// A CSV file (a header row, then rows; no quoted commas, as Talus writes them) as a JSON array
/// of objects; fields that read as numbers are numbers, "nan" and empty fields null. "[]" when
/// the file is absent.
std::string csvAsJson(const std::string& path);

} // namespace talus::ensemble
