// A parsed configuration tree that remembers where every value came from.
//
// Scene sections read their keys through typed getters; a missing, mistyped or out-of-range
// value throws InputError naming file, line and key path. Every key a reader asks for is
// remembered, so keys nobody asked for can be reported afterwards with the closest valid name.
#pragma once

#include "io/common/input_error.h"

#include <Eigen/Dense>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

namespace talus {

class ConfigTable;

struct ConfigValue {
  using Array = std::vector<ConfigValue>;
  std::variant<double, bool, std::string, Array, std::shared_ptr<ConfigTable>> data;
  bool isInteger = false; ///< number was written without a decimal point
  int line = 0;
  bool fromCommandLine = false; ///< given with --set rather than in the file

  bool isNumber() const { return std::holds_alternative<double>(data); }
  bool isString() const { return std::holds_alternative<std::string>(data); }
  bool isBool() const { return std::holds_alternative<bool>(data); }
  bool isArray() const { return std::holds_alternative<Array>(data); }
  bool isTable() const { return std::holds_alternative<std::shared_ptr<ConfigTable>>(data); }
  std::string typeName() const;
};

class ConfigTable {
public:
  ConfigTable(std::string file, std::string path, int line)
      : file_(std::move(file)), path_(std::move(path)), line_(line) {}

  void set(const std::string& key, ConfigValue v) { values_[key] = std::move(v); }

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  int line() const { return line_; }
  int lineOf(const std::string& key) const;
  std::string keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  bool has(const std::string& key) const;
  /// Throws InputError about `key` (or about this table when key is empty).
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

  double number(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  /// Finite and > 0 (or >= 0 when allowZero).
  double positive(const std::string& key) const;
  double positive(const std::string& key, double fallback, bool allowZero = false) const;
  /// Finite and inside [lo, hi] (bounds inclusive unless open).
  double inRange(const std::string& key, double fallback, double lo, double hi, bool openLo = false,
                 bool openHi = false) const;
  long integer(const std::string& key, long fallback, long lo, long hi) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  /// One of `choices`; the message lists them.
  std::string choice(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& choices) const;
  Eigen::Vector3d vec3(const std::string& key) const;
  Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& fallback) const;
  std::vector<double> numbers(const std::string& key) const;
  /// An array of strings.
  std::vector<std::string> strings(const std::string& key) const;
  const ConfigTable* table(const std::string& key) const; ///< nullptr when absent
  std::vector<const ConfigTable*> tables(const std::string& key) const; ///< array of tables

  /// Throws on the first key (depth first) that no reader asked for, suggesting the closest
  /// name that was asked for.
  void checkAllUsed() const;

  /// Overwrite (or add) a value at a dotted path; used by `--set`.
  void assign(const std::vector<std::string>& path, ConfigValue v);
  const std::map<std::string, ConfigValue>& values() const { return values_; }
  /// Every value, keys sorted, numbers exact: equal for equal configurations (names a run).
  std::string canonicalText() const;
  /// Every value as a line "dotted.key = value" (arrays of tables as key[i].sub), keys sorted,
  /// numbers exact: what a checkpoint records of its scene to name a key that changed.
  std::string keyLines() const;

  /// Missing required key: blames a present key that looks like a typo of it, if any.
  [[noreturn]] void missing(const std::string& key) const;

private:
  const ConfigValue* find(const std::string& key) const;
  std::string file_, path_;
  int line_;
  std::map<std::string, ConfigValue> values_;
  mutable std::set<std::string> asked_;
};

/// Edit distance, used for "did you mean" suggestions.
int editDistance(const std::string& a, const std::string& b);

} // namespace talus
