#include "io/config/toml_reader.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <toml++/toml.h>

namespace talus {

namespace {

ConfigValue convert(const toml::node& node, const std::string& file, const std::string& path);

std::shared_ptr<ConfigTable> convertTable(const toml::table& tbl, const std::string& file,
                                          const std::string& path) {
  auto out = std::make_shared<ConfigTable>(file, path, int(tbl.source().begin.line));
  for (const auto& [key, node] : tbl) {
    const std::string k(key.str());
    out->set(k, convert(node, file, path.empty() ? k : path + "." + k));
  }
  return out;
}

ConfigValue convert(const toml::node& node, const std::string& file, const std::string& path) {
  ConfigValue v;
  v.line = int(node.source().begin.line);
  if (auto i = node.as_integer()) {
    v.data = double(i->get());
    v.isInteger = true;
  } else if (auto f = node.as_floating_point()) {
    v.data = f->get();
  } else if (auto b = node.as_boolean()) {
    v.data = b->get();
  } else if (auto s = node.as_string()) {
    v.data = s->get();
  } else if (auto a = node.as_array()) {
    ConfigValue::Array arr;
    size_t i = 0;
    for (const auto& e : *a) arr.push_back(convert(e, file, path + "[" + std::to_string(i++) + "]"));
    v.data = std::move(arr);
  } else if (auto t = node.as_table()) {
    v.data = convertTable(*t, file, path);
  } else {
    throw InputError(file, v.line, path, "dates and times are not supported here");
  }
  return v;
}

std::shared_ptr<ConfigTable> parse(const std::string& text, const std::string& name) {
  try {
    toml::table tbl = toml::parse(text, name);
    return convertTable(tbl, name, "");
  } catch (const toml::parse_error& e) {
    throw InputError(name, int(e.source().begin.line), "", std::string(e.description()));
  }
}

} // namespace

std::shared_ptr<ConfigTable> readTomlFile(const std::string& path, std::string* text) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path, 0, "", std::filesystem::exists(path) ? "not a regular file" : "scene file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open scene file");
  std::ostringstream s;
  s << in.rdbuf();
  if (!in) throw InputError(path, 0, "", "cannot read scene file");
  if (text) *text = s.str();
  return parse(s.str(), path);
}

std::shared_ptr<ConfigTable> readTomlString(const std::string& text, const std::string& name) {
  return parse(text, name);
}

void applyOverride(ConfigTable& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set", 0, assignment, "expected key=value");
  const std::string key = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  std::vector<std::string> path;
  std::stringstream ks(key);
  for (std::string part; std::getline(ks, part, '.');) {
    if (part.empty()) throw InputError("--set", 0, key, "empty path component");
    path.push_back(part);
  }
  ConfigValue v;
  try {
    toml::table t = toml::parse("v = " + value);
    v = convert(*t.get("v"), "--set", key);
  } catch (const toml::parse_error&) {
    v.data = value; // bare word: a string such as a boundary type or a file name
  }
  root.assign(path, std::move(v));
}

} // namespace talus
