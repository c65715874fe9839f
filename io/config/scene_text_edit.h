// A scene file's text with `--set` assignments written into it, for a scene a user keeps (the
// calibrated scene of `talus calibrate`): the file stays as its author wrote it, comments and
// order included, and only the assigned values change.
#pragma once

#include <string>
#include <vector>

namespace talus {

struct SceneTextEdit {
  std::string text;
  /// Assignments that could not be written in place (a key inside an inline table, a value
  /// spanning lines, a sub-table of an array of tables): the caller reports them.
  std::vector<std::string> unplaced;
};

/// `assignments` are "section.key=value" as `--set` takes them (arrays of tables by index or by
/// name: "materials.rock.density=2500"). A key present in its table gets the new value (a
/// trailing comment kept); an absent key is added at the end of its table; an absent table
/// [a.b] is added at the end of the file. A value that is not TOML is written as a string, as
/// `--set` reads it. When `baseDir` is given, string values naming a file or folder relative to
/// it (as scene files name terrain and polygons) become absolute, so the text can be saved
/// elsewhere. Throws std::invalid_argument for an assignment without '=' or key.
SceneTextEdit assignInSceneText(const std::string& text, const std::vector<std::string>& assignments,
                                const std::string& baseDir = "");

} // namespace talus
