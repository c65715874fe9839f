#include "io/scene/contact_law_table.h"

#include "engine/contact_laws.h"

namespace talus {

namespace {

struct LawRow {
  const char* name;
  std::vector<const char*> parameters; ///< keys the reader asks for (without prefix)
  std::shared_ptr<const ContactLaw> (*read)(const ConfigTable& t, const std::string& prefix);
};

std::shared_ptr<const ContactLaw> readCoulomb(const ConfigTable& t, const std::string& prefix) {
  return makeContactLaw(CoulombLaw{Real(t.inRange(prefix + "friction", 0, 0, 10))});
}

const std::vector<LawRow>& table() {
  static const std::vector<LawRow> rows{
      {"sticky", {}, [](const ConfigTable&, const std::string&) { return makeContactLaw(StickyLaw{}); }},
      {"slip", {}, [](const ConfigTable&, const std::string&) { return makeContactLaw(SlipLaw{}); }},
      {"friction", {"friction"}, readCoulomb}, // Coulomb; "coulomb" is the same row
      {"coulomb", {"friction"}, readCoulomb},
  };
  return rows;
}

} // namespace

std::vector<std::string> contactLawNames() {
  std::vector<std::string> n;
  for (const auto& r : table()) n.push_back(r.name);
  return n;
}

std::shared_ptr<const ContactLaw> readContactLaw(const ConfigTable& t, const std::string& key,
                                                 const std::string& fallback, const std::string& prefix,
                                                 bool allowOpen) {
  const auto it = t.values().find(key);
  const ConfigTable* inline_ = it != t.values().end() && it->second.isTable() ? t.table(key) : nullptr;
  const ConfigTable& src = inline_ ? *inline_ : t;
  const std::string lawKey = inline_ ? "law" : key;
  const std::string pre = inline_ ? "" : prefix;
  std::vector<std::string> names = contactLawNames();
  if (allowOpen) names.push_back("open");
  const std::string name = src.choice(lawKey, inline_ ? "" : fallback, names);
  if (name == "open") return nullptr;
  for (const auto& row : table()) {
    if (name != row.name) continue;
    for (const char* p : row.parameters)
      if (!src.has(pre + p)) src.fail(lawKey, "'" + name + "' needs '" + pre + p + "'");
    // A parameter of another law left in the table (walls = "slip" with a wall_friction) is
    // checked to be a number but otherwise unused, as before laws were a table.
    for (const auto& other : table())
      for (const char* p : other.parameters)
        if (src.has(pre + p)) src.number(pre + p);
    return row.read(src, pre);
  }
  src.fail(lawKey, "unknown contact law '" + name + "'");
}

} // namespace talus
