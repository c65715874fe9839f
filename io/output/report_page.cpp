#include "io/output/report_page.h"

#include "io/common/atomic_file.h"
#include "io/common/json_text.h"
#include "io/common/write_error.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace talus {

namespace fs = std::filesystem;

namespace {

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8;
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

/// JSON inside a <script> block: "</" would end the block, so it is written "<\/".
std::string scriptSafe(std::string json) {
  for (size_t p = json.find("</"); p != std::string::npos; p = json.find("</", p + 3)) json.replace(p, 2, "<\\/");
  return json;
}

std::string mimeOf(const std::string& name) {
  const std::string ext = fs::path(name).extension().string();
  return ext == ".png" ? "image/png" : ext == ".gif" ? "image/gif" : ext == ".mp4" ? "video/mp4" : "";
}

/// The pictures a page shows: quick-looks of maps, plots, and the film (the MP4, else the GIF).
bool shown(const std::string& f, bool haveMp4) {
  if (f.rfind("maps/", 0) == 0 || f.rfind("plots/", 0) == 0 || f == "runout.png") return mimeOf(f) == "image/png";
  return f == "animation.mp4" || (f == "animation.gif" && !haveMp4);
}

} // namespace

void writeReportPage(const std::string& dir, const std::string& summaryJson, const std::vector<std::string>& files) {
  const fs::path root(dir);
  const std::string summary = summaryJson.empty() ? "{}" : summaryJson;
  bool haveMp4 = false;
  for (const auto& f : files) haveMp4 = haveMp4 || (f == "animation.mp4" && fs::exists(root / f));
  std::string media = "{";
  for (const auto& f : files) {
    if (!shown(f, haveMp4) || !fs::exists(root / f)) continue;
    if (media.size() > 1) media += ",\n";
    media += jsonString(f) + ": \"data:" + mimeOf(f) + ";base64," + base64(readBytes(root / f)) + "\"";
  }
  media += "}";
  std::string page = reportPageTemplate();
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"%%TALUS_SUMMARY%%", scriptSafe(summary)},
                                   std::pair<std::string, std::string>{"%%TALUS_MEDIA%%", scriptSafe(media)}}) {
    const size_t p = page.find(key);
    if (p != std::string::npos) page.replace(p, key.size(), value);
  }
  writeAtomically((root / "report.html").string(), [&](const std::string& tmp) { writeFileBytes(tmp, page); });
}

} // namespace talus
