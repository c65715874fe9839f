#include "io/scene/avaframe_scene.h"

#include "engine/resistance_law.h"
#include "io/terrain/avaframe_folder.h"
#include "io/terrain/terrain_loader.h"

#include <cmath>
#include <filesystem>

namespace talus {

namespace {

ConfigValue text(const std::string& s) {
  ConfigValue v;
  v.data = s;
  return v;
}
ConfigValue number(double d) {
  ConfigValue v;
  v.data = d;
  return v;
}
ConfigValue flag(bool b) {
  ConfigValue v;
  v.data = b;
  return v;
}

/// The table under `key` of `parent`, created when absent (fails when `key` holds a value).
ConfigTable* childTable(ConfigTable& parent, const std::string& key) {
  if (parent.table(key)) return std::get<std::shared_ptr<ConfigTable>>(parent.values().at(key).data).get();
  auto child = std::make_shared<ConfigTable>(parent.file(), parent.keyPath(key), parent.line());
  ConfigValue v;
  v.data = child;
  parent.set(key, v);
  return child.get();
}

/// Adds `table` to the array of tables `parent.key` (created when absent), first or last.
void addTable(ConfigTable& parent, const std::string& key, std::shared_ptr<ConfigTable> table, bool first) {
  ConfigValue::Array all;
  if (parent.values().count(key)) {
    const ConfigValue& own = parent.values().at(key);
    if (!own.isArray()) parent.fail(key, "expected an array of tables ([[" + parent.keyPath(key) + "]])");
    all = std::get<ConfigValue::Array>(own.data);
  }
  ConfigValue v;
  v.data = std::move(table);
  all.insert(first ? all.begin() : all.end(), v);
  ConfigValue list;
  list.data = all;
  parent.set(key, list);
}

/// AvaFrame's `res` simulation type: the RES/ areas as a [[terrain.regions]] entry with the drag
/// cResH (engine/resistance_law.h) and the detrainment detK (engine/detrainment.h; off with
/// `detrainment = false`, AvaFrame's switch), when `resistance = true`.
void addResistance(const ConfigTable& av, const AvaFrameFolder& folder, ConfigTable& ter, std::vector<std::string>& notes) {
  const bool on = av.boolean("resistance", false);
  const double cRes = av.positive("resistance_coefficient", 0.01); // AvaFrame's cResH default (1/m)
  const bool detrain = av.boolean("detrainment", true);               // AvaFrame's detrainment = True
  const double detK = av.positive("detrainment_coefficient", ResistedLaw::kDetrainment); // its detK (Pa)
  if (!on) {
    for (const char* k : {"resistance_coefficient", "detrainment", "detrainment_coefficient"})
      if (av.has(k)) av.fail(k, "needs resistance = true");
    if (folder.resistance)
      notes.push_back(folder.resistance->path + ": resistance areas not used (set avaframe.resistance = true to apply "
                                                "them: AvaFrame's res simulation type)");
    return;
  }
  if (!folder.resistance) av.fail("resistance", folder.dir + "/Inputs/RES: no resistance shapefile");
  auto region = std::make_shared<ConfigTable>(ter.file(), ter.keyPath("regions"), ter.line());
  region->set("polygon", text(std::filesystem::absolute(folder.resistance->path).string()));
  region->set("resistance", number(cRes));
  if (!detrain && av.has("detrainment_coefficient")) av.fail("detrainment_coefficient", "needs detrainment = true");
  region->set("detrainment", number(detrain ? detK : 0.0));
  addTable(ter, "regions", region, true); // the scene's own regions after it: they win where they overlap
  notes.push_back(folder.resistance->path + ": resistance areas applied, drag cResH " + std::to_string(cRes).substr(0, 6) +
                  " 1/m" + (detrain ? ", detrainment detK " + std::to_string(detK).substr(0, 6) + " Pa" : ", no detrainment") +
                  " (AvaFrame's res)");
}

/// AvaFrame's DAM/ lines as a [[structures]] dam (engine/dam_sdf.h), when `dams = true`.
void addDams(const ConfigTable& av, const AvaFrameFolder& folder, ConfigTable& root, std::vector<std::string>& notes) {
  if (!av.boolean("dams", false)) {
    if (!folder.damFile.empty())
      notes.push_back(folder.damFile + ": dam line not used (set avaframe.dams = true to build it as a [[structures]] dam)");
    return;
  }
  if (folder.damFile.empty()) av.fail("dams", folder.dir + "/Inputs/DAM: no dam shapefile");
  auto dam = std::make_shared<ConfigTable>(root.file(), root.keyPath("structures"), root.line());
  dam->set("name", text("dam"));
  dam->set("shape", text("dam"));
  dam->set("line_file", text(std::filesystem::absolute(folder.damFile).string()));
  addTable(root, "structures", dam, false);
  notes.push_back(folder.damFile + ": dam line built as the structure 'dam' (crest from the line's z, flanks at its slope)");
}

std::vector<std::string> materialNames(const ConfigTable& root) {
  std::vector<std::string> names;
  if (!root.values().count("materials") || !root.values().at("materials").isArray()) return names;
  for (const auto& e : std::get<ConfigValue::Array>(root.values().at("materials").data))
    if (e.isTable()) {
      const auto& t = *std::get<std::shared_ptr<ConfigTable>>(e.data);
      if (t.values().count("name") && t.values().at("name").isString())
        names.push_back(std::get<std::string>(t.values().at("name").data));
    }
  return names;
}

std::string material(const ConfigTable& av, const std::string& key, const std::vector<std::string>& names, bool required) {
  if (!av.has(key)) {
    if (names.size() == 1) return names.front(); // the scene's only material
    if (required) av.fail("", "missing required key '" + key + "' (the scene has several materials)");
    return "";
  }
  const std::string m = av.string(key);
  for (const auto& n : names)
    if (n == m) return m;
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  av.fail(key, "no material named '" + m + "' (materials: " + list + ")");
}

/// A [[bodies]] table for an area file: a release or a cover of `mat`, AvaFrame's thickness
/// (slope-normal) from the attribute or `thickness` (NaN: use the attribute).
std::shared_ptr<ConfigTable> areaBody(const AvaFrameAreas& a, const std::string& folderKind, const std::string& kind,
                                      const std::string& mat, double thickness) {
  auto t = std::make_shared<ConfigTable>(a.path, "avaframe[" + folderKind + "/" + a.name + "]", 0);
  t->set("name", text(a.name));
  t->set("kind", text(kind));
  t->set("material", text(mat));
  t->set("polygon", text(std::filesystem::absolute(a.path).string()));
  if (std::isnan(thickness)) t->set("thickness_attribute", text(a.thicknessField));
  else t->set("thickness", number(thickness));
  t->set("thickness_direction", text("slope_normal")); // AvaFrame's thickness is normal to the slope
  return t;
}

} // namespace

std::string avaFrameOverride(const std::string& dir) {
  std::string quoted = "\"";
  for (char c : std::filesystem::absolute(dir).lexically_normal().string()) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  return "avaframe.directory=" + quoted + "\"";
}

void expandAvaFrame(ConfigTable& root, std::vector<std::string>& notes) {
  const ConfigTable* av = root.table("avaframe");
  if (!av) return;
  const std::string dir = resolveScenePath(av->file(), av->string("directory"));
  AvaFrameFolder folder;
  try {
    folder = readAvaFrameFolder(dir);
  } catch (const InputError& e) {
    av->fail("directory", e.what());
  } catch (const std::filesystem::filesystem_error& e) { // a path the system refuses (too long, no access)
    av->fail("directory", e.what());
  }
  const auto names = materialNames(root);
  const AvaFrameAreas* rel = nullptr;
  try {
    rel = &folder.release(av->string("release_scenario", ""));
  } catch (const InputError& e) {
    av->fail("release_scenario", e.what());
  }
  const std::string relMaterial = material(*av, "release_material", names, true);
  const double relTh = av->has("release_thickness") ? av->positive("release_thickness") : NAN;
  if (std::isnan(relTh) && rel->thicknessField.empty())
    av->fail("", rel->path + " has no thickness attribute: give release_thickness (m, AvaFrame's relTh)");
  const std::string entMaterial = av->has("entrainment_material") ? material(*av, "entrainment_material", names, true) : "";
  double entTh = av->has("entrainment_thickness") ? av->positive("entrainment_thickness") : NAN;
  for (const char* k : {"entrainment_thickness", "erosion_energy"})
    if (av->has(k) && entMaterial.empty()) av->fail(k, "needs entrainment_material (the material of the ENT/ covers)");
  if (!entMaterial.empty() && !folder.entrainment)
    av->fail("entrainment_material", folder.dir + "/Inputs/ENT: no entrainment shapefile");

  ConfigTable* ter = childTable(root, "terrain");
  for (const char* k : {"dem", "synthetic", "plane", "sdf"})
    if (ter->has(k)) ter->fail(k, std::string("the AvaFrame folder (avaframe.directory) brings the DEM; remove '") + k + "'");
  ter->set("dem", text(std::filesystem::absolute(folder.dem).string()));
  if (!ter->has("fill_nodata")) ter->set("fill_nodata", flag(true)); // AvaFrame DEMs end in no-data margins
  if (!ter->has("crs") && folder.demCrsWkt.empty() && !rel->crsWkt.empty()) ter->set("crs", text(rel->crsWkt));

  ConfigValue::Array bodies;
  auto add = [&](std::shared_ptr<ConfigTable> t) {
    ConfigValue v;
    v.data = t;
    bodies.push_back(v);
  };
  add(areaBody(*rel, "REL", "release", relMaterial, relTh));
  // AvaFrame's SECREL/: released when the flow reaches them (a trigger of a few centimetres of
  // flow: AvaFrame releases them when its first particle enters).
  if (av->boolean("secondary_release", false)) {
    if (!folder.secondaryRelease) av->fail("secondary_release", folder.dir + "/Inputs/SECREL: no secondary release shapefile");
    auto sec = areaBody(*folder.secondaryRelease, "SECREL", "release", relMaterial,
                        folder.secondaryRelease->thicknessField.empty() ? (std::isnan(relTh) ? 1.0 : relTh) : NAN);
    sec->set("trigger_thickness", number(av->positive("secondary_trigger_thickness", 0.05)));
    add(sec);
  } else if (folder.secondaryRelease) {
    notes.push_back(folder.secondaryRelease->path + ": secondary release areas not used (set avaframe.secondary_release = "
                                                    "true to hold them until the flow reaches them)");
  }
  if (!entMaterial.empty()) {
    // AvaFrame: thickness from the file, else entThIfMissingInShp = 0.3 m.
    if (std::isnan(entTh) && folder.entrainment->thicknessField.empty()) {
      entTh = 0.3;
      notes.push_back(folder.entrainment->path + ": no thickness attribute, AvaFrame's default 0.3 m used");
    }
    auto ent = areaBody(*folder.entrainment, "ENT", "layer", entMaterial, entTh);
    // AvaFrame's entEroEnergy; a cover under a cell thick erodes as com1DFA's (io/scene/erodible_cover_reader.h).
    if (av->has("erosion_energy")) ent->set("erosion_energy", number(av->positive("erosion_energy")));
    add(ent);
  } else if (folder.entrainment) {
    notes.push_back(folder.entrainment->path + ": entrainment areas not used (set avaframe.entrainment_material to "
                                               "add them as erodible covers)");
  }
  addResistance(*av, folder, *ter, notes);
  addDams(*av, folder, root, notes);
  if (root.values().count("bodies")) {
    const ConfigValue& own = root.values().at("bodies");
    if (!own.isArray()) root.fail("bodies", "expected an array of tables ([[bodies]])");
    for (const auto& e : std::get<ConfigValue::Array>(own.data)) bodies.push_back(e);
  }
  ConfigValue all;
  all.data = bodies;
  root.set("bodies", all);

  ConfigTable* out = childTable(root, "output");
  if (!out->has("maps")) out->set("maps", flag(true));
  if (!out->has("peak_files")) out->set("peak_files", flag(true));
  if (!folder.thalweg.empty()) { // the run-out of an ensemble is measured along AIMEC's path
    ConfigTable* ens = childTable(root, "ensemble");
    if (!ens->has("path")) ens->set("path", text(std::filesystem::absolute(folder.thalwegFile).string()));
  }
  for (const auto& n : folder.notes) notes.push_back(n);
  notes.push_back("avaframe: " + folder.name + ", release scenario " + rel->name + " (" +
                  std::to_string(rel->features.size()) + " feature(s)), " +
                  (entMaterial.empty() ? std::string("no entrainment") : "entrainment " + folder.entrainment->name) +
                  (folder.thalweg.empty() ? ", no AIMEC path" : ", AIMEC path " + folder.thalwegFile));
}

} // namespace talus
