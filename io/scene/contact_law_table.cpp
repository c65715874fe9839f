#include "io/scene/contact_law_table.h"

#include "engine/contact_laws.h"
#include "engine/samosat_law.h"
#include "engine/voellmy_law.h"

namespace talus {

namespace {

struct LawRow {
  const char* name;
  std::vector<const char*> parameters; ///< keys the reader asks for (without prefix)
  std::vector<const char*> required;   ///< of those, the ones without a default
  std::shared_ptr<const ContactLaw> (*read)(const ConfigTable& t, const std::string& prefix);
};

std::shared_ptr<const ContactLaw> readCoulomb(const ConfigTable& t, const std::string& prefix) {
  return makeContactLaw(CoulombLaw{Real(t.inRange(prefix + "friction", 0, 0, 10))});
}

std::shared_ptr<const ContactLaw> readVoellmy(const ConfigTable& t, const std::string& pre) {
  VoellmyLaw v;
  v.mu = Real(t.inRange(pre + "friction", v.mu, 0, 10));
  v.xi = Real(t.positive(pre + "xi", v.xi));
  return makeContactLaw(v);
}

/// samosAT with AvaFrame's defaults, or its Small/Medium sets (mu 0.22 / 0.17, for releases under
/// 25 000 / 60 000 m3: AvaFrame com1DFACfg.ini, frictModel samosATSmall/Medium).
std::shared_ptr<const ContactLaw> readSamosAt(const ConfigTable& t, const std::string& pre, double mu) {
  SamosAtLaw s;
  s.mu = Real(t.inRange(pre + "friction", mu, 0, 10));
  s.tau0 = Real(t.positive(pre + "min_shear", s.tau0, true));
  s.rs0 = Real(t.positive(pre + "rs0", s.rs0));
  s.kappa = Real(t.positive(pre + "kappa", s.kappa));
  s.roughness = Real(t.positive(pre + "roughness", s.roughness));
  s.b = Real(t.number(pre + "b", s.b));
  return makeContactLaw(s);
}

const std::vector<const char*> kSamosAtKeys{"friction", "min_shear", "rs0", "kappa", "roughness", "b"};

const std::vector<LawRow>& table() {
  static const std::vector<LawRow> rows{
      {"sticky", {}, {}, [](const ConfigTable&, const std::string&) { return makeContactLaw(StickyLaw{}); }},
      {"slip", {}, {}, [](const ConfigTable&, const std::string&) { return makeContactLaw(SlipLaw{}); }},
      {"friction", {"friction"}, {"friction"}, readCoulomb}, // Coulomb; "coulomb" is the same row
      {"coulomb", {"friction"}, {"friction"}, readCoulomb},
      {"voellmy", {"friction", "xi"}, {}, readVoellmy},
      {"samosat", kSamosAtKeys, {}, [](const ConfigTable& t, const std::string& p) { return readSamosAt(t, p, 0.155); }},
      {"samosat_medium", kSamosAtKeys, {}, [](const ConfigTable& t, const std::string& p) { return readSamosAt(t, p, 0.17); }},
      {"samosat_small", kSamosAtKeys, {}, [](const ConfigTable& t, const std::string& p) { return readSamosAt(t, p, 0.22); }},
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
    for (const char* p : row.required)
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
