#include "io/config/config_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace talus {

std::string ConfigValue::typeName() const {
  if (isNumber()) return isInteger ? "integer" : "number";
  if (isBool()) return "boolean";
  if (isString()) return "string";
  if (isArray()) return "array";
  return "table";
}

namespace {
std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
} // namespace

const ConfigValue* ConfigTable::find(const std::string& key) const {
  asked_.insert(key);
  auto it = values_.find(key);
  return it == values_.end() ? nullptr : &it->second;
}

bool ConfigTable::has(const std::string& key) const { return find(key) != nullptr; }

int ConfigTable::lineOf(const std::string& key) const {
  auto it = values_.find(key);
  return it == values_.end() ? line_ : it->second.line;
}

void ConfigTable::fail(const std::string& key, const std::string& message) const {
  auto it = key.empty() ? values_.end() : values_.find(key);
  const bool cli = it != values_.end() && it->second.fromCommandLine;
  throw InputError(file_, key.empty() ? line_ : lineOf(key), key.empty() ? path_ : keyPath(key),
                   message + (cli ? " (given with --set)" : ""));
}

void ConfigTable::missing(const std::string& key) const {
  for (const auto& [k, v] : values_)
    if (!asked_.count(k) && editDistance(k, key) <= std::max<int>(2, int(key.size()) / 3))
      throw InputError(file_, v.line, keyPath(k), "unknown key (did you mean '" + key + "'?)");
  fail("", "missing required key '" + key + "'");
}

double ConfigTable::number(const std::string& key) const {
  const ConfigValue* v = find(key);
  if (!v) missing(key);
  if (!v->isNumber()) fail(key, "expected a number, got a " + v->typeName());
  const double d = std::get<double>(v->data);
  if (!std::isfinite(d)) fail(key, "must be finite (got " + formatNumber(d) + ")");
  return d;
}

double ConfigTable::number(const std::string& key, double fallback) const {
  return find(key) ? number(key) : fallback;
}

double ConfigTable::positive(const std::string& key) const {
  const double d = number(key);
  if (!(d > 0)) fail(key, "must be positive (got " + formatNumber(d) + ")");
  return d;
}

double ConfigTable::positive(const std::string& key, double fallback, bool allowZero) const {
  if (!find(key)) return fallback;
  const double d = number(key);
  if (allowZero ? !(d >= 0) : !(d > 0))
    fail(key, std::string("must be ") + (allowZero ? "non-negative" : "positive") + " (got " +
                  formatNumber(d) + ")");
  return d;
}

double ConfigTable::inRange(const std::string& key, double fallback, double lo, double hi,
                            bool openLo, bool openHi) const {
  if (!find(key)) return fallback;
  const double d = number(key);
  const bool okLo = openLo ? d > lo : d >= lo;
  const bool okHi = openHi ? d < hi : d <= hi;
  if (!okLo || !okHi)
    fail(key, "must be in " + std::string(openLo ? "(" : "[") + formatNumber(lo) + ", " +
                  formatNumber(hi) + (openHi ? ")" : "]") + " (got " + formatNumber(d) + ")");
  return d;
}

long ConfigTable::integer(const std::string& key, long fallback, long lo, long hi) const {
  const ConfigValue* v = find(key);
  if (!v) return fallback;
  if (!v->isNumber() || !v->isInteger) fail(key, "expected an integer, got a " + v->typeName());
  const double d = std::get<double>(v->data);
  if (d < double(lo) || d > double(hi))
    fail(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                  formatNumber(d) + ")");
  return long(d);
}

bool ConfigTable::boolean(const std::string& key, bool fallback) const {
  const ConfigValue* v = find(key);
  if (!v) return fallback;
  if (!v->isBool()) fail(key, "expected true or false, got a " + v->typeName());
  return std::get<bool>(v->data);
}

std::string ConfigTable::string(const std::string& key) const {
  const ConfigValue* v = find(key);
  if (!v) missing(key);
  if (!v->isString()) fail(key, "expected a string, got a " + v->typeName());
  return std::get<std::string>(v->data);
}

std::string ConfigTable::string(const std::string& key, const std::string& fallback) const {
  return find(key) ? string(key) : fallback;
}

std::string ConfigTable::choice(const std::string& key, const std::string& fallback,
                                const std::vector<std::string>& choices) const {
  const std::string s = string(key, fallback);
  if (std::find(choices.begin(), choices.end(), s) != choices.end()) return s;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  std::string best;
  int bestD = 3;
  for (const auto& c : choices) {
    const int d = editDistance(s, c);
    if (d < bestD) bestD = d, best = c;
  }
  fail(key, "'" + s + "' is not one of: " + list +
                (best.empty() ? "" : " (did you mean '" + best + "'?)"));
}

std::vector<double> ConfigTable::numbers(const std::string& key) const {
  const ConfigValue* v = find(key);
  if (!v) missing(key);
  if (!v->isArray()) fail(key, "expected an array of numbers, got a " + v->typeName());
  std::vector<double> out;
  for (const auto& e : std::get<ConfigValue::Array>(v->data)) {
    if (!e.isNumber()) fail(key, "expected an array of numbers, found a " + e.typeName());
    const double d = std::get<double>(e.data);
    if (!std::isfinite(d)) fail(key, "must contain finite numbers");
    out.push_back(d);
  }
  return out;
}

std::vector<std::string> ConfigTable::strings(const std::string& key) const {
  const ConfigValue* v = find(key);
  if (!v) missing(key);
  if (!v->isArray()) fail(key, "expected an array of strings, got a " + v->typeName());
  std::vector<std::string> out;
  for (const auto& e : std::get<ConfigValue::Array>(v->data)) {
    if (!e.isString()) fail(key, "expected an array of strings, found a " + e.typeName());
    out.push_back(std::get<std::string>(e.data));
  }
  return out;
}

Eigen::Vector3d ConfigTable::vec3(const std::string& key) const {
  const auto n = numbers(key);
  if (n.size() != 3)
    fail(key, "expected 3 numbers [x, y, z], got " + std::to_string(n.size()));
  return {n[0], n[1], n[2]};
}

Eigen::Vector3d ConfigTable::vec3(const std::string& key, const Eigen::Vector3d& fallback) const {
  return find(key) ? vec3(key) : fallback;
}

const ConfigTable* ConfigTable::table(const std::string& key) const {
  const ConfigValue* v = find(key);
  if (!v) return nullptr;
  if (!v->isTable()) fail(key, "expected a table, got a " + v->typeName());
  return std::get<std::shared_ptr<ConfigTable>>(v->data).get();
}

std::vector<const ConfigTable*> ConfigTable::tables(const std::string& key) const {
  std::vector<const ConfigTable*> out;
  const ConfigValue* v = find(key);
  if (!v) return out;
  if (!v->isArray()) fail(key, "expected an array of tables ([[" + key + "]]), got a " + v->typeName());
  for (const auto& e : std::get<ConfigValue::Array>(v->data)) {
    if (!e.isTable()) fail(key, "expected an array of tables ([[" + key + "]])");
    out.push_back(std::get<std::shared_ptr<ConfigTable>>(e.data).get());
  }
  return out;
}

void ConfigTable::checkAllUsed() const {
  for (const auto& [key, v] : values_) {
    if (!asked_.count(key)) {
      std::string best;
      int bestD = std::max<int>(2, int(key.size()) / 3) + 1;
      for (const auto& a : asked_) {
        const int d = editDistance(key, a);
        if (d < bestD) bestD = d, best = a;
      }
      throw InputError(file_, v.line, keyPath(key),
                       "unknown key" + (best.empty() ? std::string() : " (did you mean '" + best + "'?)"));
    }
    if (v.isTable()) std::get<std::shared_ptr<ConfigTable>>(v.data)->checkAllUsed();
    if (v.isArray())
      for (const auto& e : std::get<ConfigValue::Array>(v.data))
        if (e.isTable()) std::get<std::shared_ptr<ConfigTable>>(e.data)->checkAllUsed();
  }
}

void ConfigTable::assign(const std::vector<std::string>& path, ConfigValue v) {
  const std::string dotted = [&] {
    std::string s;
    for (const auto& p : path) s += (s.empty() ? "" : ".") + p;
    return s;
  }();
  ConfigTable* t = this;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    auto it = t->values_.find(path[i]);
    if (it == t->values_.end()) {
      // Create the missing table so --set can add a whole section key by key.
      auto child = std::make_shared<ConfigTable>(file_, t->keyPath(path[i]), 0);
      ConfigValue cv;
      cv.data = child;
      t->values_[path[i]] = cv;
      t = child.get();
      continue;
    }
    ConfigValue& cur = it->second;
    if (cur.isTable()) {
      t = std::get<std::shared_ptr<ConfigTable>>(cur.data).get();
    } else if (cur.isArray()) {
      // An array of tables: select the element by index or by its `name`.
      auto& arr = std::get<ConfigValue::Array>(cur.data);
      const std::string& sel = path[i + 1];
      ConfigTable* found = nullptr;
      char* end = nullptr;
      const long idx = std::strtol(sel.c_str(), &end, 10);
      if (end && *end == '\0' && idx >= 0 && size_t(idx) < arr.size() && arr[idx].isTable())
        found = std::get<std::shared_ptr<ConfigTable>>(arr[idx].data).get();
      for (auto& e : arr)
        if (!found && e.isTable()) {
          auto* et = std::get<std::shared_ptr<ConfigTable>>(e.data).get();
          auto n = et->values_.find("name");
          if (n != et->values_.end() && n->second.isString() && std::get<std::string>(n->second.data) == sel)
            found = et;
        }
      if (!found)
        throw InputError("--set", 0, dotted, "no element '" + sel + "' in [[" + path[i] + "]] (use an index or a name)");
      t = found;
      ++i;
      if (i + 1 >= path.size()) throw InputError("--set", 0, dotted, "path names a table, not a key");
    } else {
      throw InputError("--set", 0, dotted, "'" + path[i] + "' is a value, not a table");
    }
  }
  auto it = t->values_.find(path.back());
  if (it != t->values_.end() && (it->second.isTable() ||
                                 (it->second.isArray() && !std::get<ConfigValue::Array>(it->second.data).empty() &&
                                  std::get<ConfigValue::Array>(it->second.data).front().isTable())))
    throw InputError("--set", 0, dotted, "cannot replace a table with a value");
  v.line = 0;
  v.fromCommandLine = true;
  t->values_[path.back()] = std::move(v);
}

namespace {
void canonical(const ConfigValue& v, std::string& out) {
  char buf[40];
  if (v.isNumber()) std::snprintf(buf, sizeof buf, "%.17g", std::get<double>(v.data)), out += buf;
  else if (v.isBool()) out += std::get<bool>(v.data) ? "true" : "false";
  else if (v.isString()) out += "\"" + std::get<std::string>(v.data) + "\"";
  else if (v.isTable()) out += std::get<std::shared_ptr<ConfigTable>>(v.data)->canonicalText();
  else {
    out += "[";
    for (const auto& e : std::get<ConfigValue::Array>(v.data)) canonical(e, out), out += ",";
    out += "]";
  }
}
} // namespace

std::string ConfigTable::canonicalText() const {
  std::string out = "{";
  for (const auto& [k, v] : values_) { // std::map: sorted keys
    out += k + "=";
    canonical(v, out);
    out += ";";
  }
  return out + "}";
}

namespace {
void keyLinesOf(const ConfigTable& t, const std::string& prefix, std::string& out) {
  for (const auto& [k, v] : t.values()) {
    if (v.isTable()) {
      keyLinesOf(*std::get<std::shared_ptr<ConfigTable>>(v.data), prefix + k + ".", out);
      continue;
    }
    if (v.isArray()) {
      const auto& a = std::get<ConfigValue::Array>(v.data);
      if (!a.empty() && a.front().isTable()) {
        for (size_t i = 0; i < a.size(); ++i)
          if (a[i].isTable())
            keyLinesOf(*std::get<std::shared_ptr<ConfigTable>>(a[i].data), prefix + k + "[" + std::to_string(i) + "].", out);
        continue;
      }
    }
    out += prefix + k + " = ";
    canonical(v, out);
    out += "\n";
  }
}
} // namespace

std::string ConfigTable::keyLines() const {
  std::string out;
  keyLinesOf(*this, "", out);
  return out;
}

int editDistance(const std::string& a, const std::string& b) {
  std::vector<int> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = int(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = int(i);
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

} // namespace talus
