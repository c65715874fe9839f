#include "hazard/ensemble_report.h"

#include "io/common/json_text.h"
#include "io/output/report_page.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace talus::ensemble {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string f; std::getline(s, f, ',');) out.push_back(f);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

std::string jsonValue(const std::string& field) {
  if (field.empty() || field == "nan" || field == "NaN") return "null";
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  if (end && *end == '\0' && std::isfinite(v)) return field;
  return jsonString(field);
}

} // namespace

std::string csvAsJson(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) return "[]";
  const std::vector<std::string> header = split(line);
  std::string out = "[";
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> f = split(line);
    out += out.size() > 1 ? ",\n{" : "\n{";
    for (size_t i = 0; i < header.size(); ++i)
      out += (i ? ", " : "") + jsonString(header[i]) + ": " + (i < f.size() ? jsonValue(f[i]) : "null");
    out += "}";
  }
  return out + "]";
}

void writeEnsembleReport(const std::string& dir, const std::vector<std::string>& files) {
  namespace fs = std::filesystem;
  const fs::path root(dir);
  std::string fileList;
  for (const auto& f : files) fileList += (fileList.empty() ? "" : ", ") + jsonString(f);
  const std::string summary = "{\"kind\": \"ensemble\", \"scene\": " + jsonString(root.filename().string()) +
                              ",\n\"members\": " + csvAsJson((root / "members.csv").string()) +
                              ",\n\"morris\": " + csvAsJson((root / "morris.csv").string()) +
                              ",\n\"files\": [" + fileList + "]}";
  writeReportPage(dir, summary, files);
}

} // namespace talus::ensemble
