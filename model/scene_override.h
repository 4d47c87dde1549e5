// SPDX-License-Identifier: MIT
// Scene overrides: `pastemix run SCENE.toml --set key.path=value ...` and the studies of `pastemix sweep`.
//
// A SceneDoc is the parsed scene TOML that can be edited by dotted path before the scene loader reads it,
// so a study varies any parameter without copying scene files. Path segments name table keys; inside an
// array of tables ([[material]], [[wall]], [[interaction]], [[factory]]) a segment is either an index
// ("factory.0.mass") or the element's `name` / `materials` value ("material.rock.youngs_modulus",
// "interaction.rock/steel.friction").
//
// Values are TOML literals ("2e-6", "[0, 0, 0.01]", "\"elastic_plastic\"", "true"); a bare word is taken as
// a string when the key holds a string. The new value must have the type of the old one (an integer may
// replace a float, not the reverse), and the path must exist: both errors are InputError naming the scene
// file, the line of the key (or of the deepest table found) and the path. Overrides never add keys: a
// misspelt path would otherwise be silently ignored, which is exactly what Params::finish() exists to stop.
//
// Caveat: the edited document is re-serialised for the loader, so a later scene error (a check that fails
// on the overridden value) names the scene file with the line of the re-serialised text; the override
// itself is validated here against the original lines first.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "model/scene.h"

namespace toml {
inline namespace v3 {
class table;
}
}  // namespace toml

namespace pastemix::model {

class SceneDoc {
 public:
  static SceneDoc parse_file(const std::filesystem::path& path);
  static SceneDoc parse(const std::string& text, const std::string& display_path);
  SceneDoc(const SceneDoc&);
  SceneDoc& operator=(const SceneDoc&);
  ~SceneDoc();

  // "key.path=value" (as on the command line).
  void apply(const std::string& assignment);
  void set(const std::string& path, const std::string& value_literal);
  // The current value as TOML text (for tables written in reports); throws InputError if absent.
  std::string get(const std::string& path) const;
  bool has(const std::string& path) const;

  const std::string& path() const { return path_; }
  toml::table& root() { return *root_; }
  const toml::table& root() const { return *root_; }
  std::string text() const;  // TOML of the edited document
  Scene load() const;        // the scene loader on text(), display path = the scene file

 private:
  SceneDoc() = default;
  std::string path_;
  std::unique_ptr<toml::table> root_;
};

// An override file (as `pastemix sweep` writes): one `key.path = value` per line, '#' comments. Returns the
// assignments in the form apply() takes; a malformed line is an InputError with its line.
std::vector<std::string> read_override_file(const std::filesystem::path& path);

// load_scene with overrides applied in order ("key.path=value").
Scene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides);

}  // namespace pastemix::model
