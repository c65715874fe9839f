#include "io/config/scene_text_edit.h"

#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace talus {

namespace {

namespace fs = std::filesystem;

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

/// A table of the file: its header line and the lines up to the next header.
struct Block {
  std::string path; ///< "" for the keys before the first header
  bool array = false;
  std::string index, name; ///< arrays of tables: position among its kind and its name key
  size_t first = 0, end = 0; ///< body lines [first, end)
};

/// Position of `key = ` in a line: the index of '=' or npos.
size_t assignmentOf(const std::string& line, const std::string& key) {
  const auto a = line.find_first_not_of(" \t");
  if (a == std::string::npos || line.compare(a, key.size(), key) != 0) return std::string::npos;
  const auto b = line.find_first_not_of(" \t", a + key.size());
  return b != std::string::npos && line[b] == '=' ? b : std::string::npos;
}

/// Where the value after `eq` ends (a comment's '#' outside strings, or the line's end).
size_t valueEnd(const std::string& line, size_t eq) {
  char quote = 0;
  for (size_t i = eq + 1; i < line.size(); ++i) {
    const char c = line[i];
    if (quote) {
      if (c == '\\' && quote == '"') ++i;
      else if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') quote = c;
    else if (c == '#') return i;
  }
  return line.size();
}

std::vector<Block> blocks(const std::vector<std::string>& lines) {
  std::vector<Block> out(1);
  std::vector<std::pair<std::string, int>> arrayCounts;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string t = trim(lines[i]);
    if (t.empty() || t[0] != '[') {
      if (out.back().array && assignmentOf(lines[i], "name") != std::string::npos) {
        const std::string v = trim(lines[i].substr(assignmentOf(lines[i], "name") + 1));
        if (v.size() >= 2 && v[0] == '"') out.back().name = v.substr(1, v.find('"', 1) - 1);
      }
      continue;
    }
    out.back().end = i;
    Block b;
    b.array = t.rfind("[[", 0) == 0;
    b.path = trim(t.substr(b.array ? 2 : 1, t.find(']') - (b.array ? 2 : 1)));
    if (b.array) {
      int n = 0;
      for (auto& c : arrayCounts)
        if (c.first == b.path) n = ++c.second;
      if (n == 0) arrayCounts.emplace_back(b.path, 0);
      b.index = std::to_string(n);
    }
    b.first = i + 1;
    out.push_back(b);
  }
  out.back().end = lines.size();
  return out;
}

std::string tomlValue(const std::string& value) {
  try {
    (void)toml::parse("v = " + value);
    return value;
  } catch (const toml::parse_error&) {
    std::string q = "\"";
    for (char c : value) q += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    return q + "\"";
  }
}

/// Writes one assignment; false when it has no place that can be written safely.
bool assign(std::vector<std::string>& lines, const std::string& key, const std::string& value) {
  const auto dot = key.rfind('.');
  const std::string prefix = dot == std::string::npos ? "" : key.substr(0, dot), leaf = key.substr(dot + 1);
  const std::vector<Block> bs = blocks(lines);
  for (const Block& b : bs) {
    const bool match = b.array ? (prefix == b.path + "." + b.index || (!b.name.empty() && prefix == b.path + "." + b.name))
                               : prefix == b.path;
    if (!match) continue;
    // An absent key goes after the table's last key (right after its header when it has none;
    // before the first header for a top-level key).
    size_t at = b.path.empty() ? b.end : b.first;
    for (size_t i = b.first; i < b.end; ++i) {
      const size_t eq = assignmentOf(lines[i], leaf);
      if (eq != std::string::npos) {
        const std::string old = trim(lines[i].substr(eq + 1, valueEnd(lines[i], eq) - eq - 1));
        if (old.rfind("\"\"\"", 0) == 0 || old.rfind("'''", 0) == 0 ||
            std::count(old.begin(), old.end(), '[') != std::count(old.begin(), old.end(), ']'))
          return false; // a value spanning lines
        const size_t end = valueEnd(lines[i], eq);
        const std::string comment = end < lines[i].size() ? "  " + lines[i].substr(end) : "";
        lines[i] = lines[i].substr(0, eq) + "= " + tomlValue(value) + comment;
        return true;
      }
      const std::string t = trim(lines[i]);
      if (!t.empty() && t[0] != '#') at = i + 1;
    }
    lines.insert(lines.begin() + long(at), leaf + " = " + tomlValue(value));
    return true;
  }
  for (const Block& b : bs)
    if (b.array && (prefix == b.path || prefix.rfind(b.path + ".", 0) == 0)) return false; // inside an array of tables
  lines.push_back("");
  lines.push_back("[" + prefix + "]");
  lines.push_back(leaf + " = " + tomlValue(value));
  return true;
}

void absolutePaths(std::vector<std::string>& lines, const fs::path& base) {
  for (auto& line : lines) {
    const auto eq = line.find('=');
    const std::string t = trim(line);
    if (eq == std::string::npos || t.empty() || t[0] == '#' || t[0] == '[') continue;
    const size_t end = valueEnd(line, eq);
    const std::string v = trim(line.substr(eq + 1, end - eq - 1));
    if (v.size() < 3 || v.front() != '"' || v.back() != '"' || v.find('"', 1) != v.size() - 1) continue;
    const fs::path p = v.substr(1, v.size() - 2);
    std::error_code ec;
    if (p.is_absolute() || !fs::exists(base / p, ec)) continue;
    const std::string comment = end < line.size() ? "  " + line.substr(end) : "";
    line = line.substr(0, eq) + "= \"" + (base / p).lexically_normal().string() + "\"" + comment;
  }
}

} // namespace

SceneTextEdit assignInSceneText(const std::string& text, const std::vector<std::string>& assignments,
                                const std::string& baseDir) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  SceneTextEdit out;
  for (const auto& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0) throw std::invalid_argument("assignment '" + a + "': expected key=value");
    if (!assign(lines, trim(a.substr(0, eq)), a.substr(eq + 1))) out.unplaced.push_back(a);
  }
  if (!baseDir.empty()) absolutePaths(lines, fs::absolute(baseDir));
  for (const auto& l : lines) out.text += l + "\n";
  return out;
}

} // namespace talus
