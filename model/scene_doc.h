// SPDX-License-Identifier: MIT
// SceneDoc: the one representation of a scene document. Loading (`pastemix run`), the overrides (`--set
// key.path=value`, `--overrides FILE`) and the studies (`pastemix sweep`, `calibrate`) all read and edit a
// scene through it; nothing else touches the TOML of a scene.
//
// Paths are dotted: segments name table keys; inside an array of tables ([[material]], [[wall]],
// [[interaction]], [[factory]]) a segment is either an index ("factory.0.mass") or the element's `name` /
// `materials` value ("material.rock.youngs_modulus", "interaction.rock/steel.friction").
//
// User overrides (apply, apply_file, set) take TOML literals ("2e-6", "[0, 0, 0.01]", "\"elastic_plastic\"",
// "true"); a bare word is taken as a string when the key holds a string. The new value must have the type of
// the old one (an integer may replace a float, not the reverse). A path the scene lacks adds the key to a
// table the scene has (`fluid.0.dynamics`; a missing table or array element is an error): it has no old type,
// and the scene loader checks it like any key, so a misspelt one is an unknown-key error at the override's
// line, not silently ignored. These errors are InputError naming where the user wrote the override (the
// overrides file and its line; for --set the scene file and the key's line).
//
// Errors found later by the scene loader name the text the user wrote: a key of the scene file its own line
// there (the document is read as parsed, never re-serialised first), a value from an overrides file that
// file's line, a value from --set the scene key's line with "(--set ...)" after the key.
//
// text() is the file as read when nothing was edited, else the edited document serialised by toml++ (sorted
// keys): that text is what a run stores and what the scene hash (model/output.h) is taken of, so a cached
// study run (calibrate rheology: runs/<hash>.h5) is found again.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.h"

namespace pastemix::model {

// Where an edited value was written: the file and line an error about it names, and a note after the key.
struct EditOrigin {
  std::string file;
  int line = 0;
  std::string note;
};

class SceneDoc {
 public:
  static SceneDoc parse_file(const std::filesystem::path& path);
  static SceneDoc parse(std::string text, std::string display_path);
  SceneDoc(const SceneDoc&);
  SceneDoc& operator=(const SceneDoc&);
  SceneDoc(SceneDoc&&) noexcept;
  SceneDoc& operator=(SceneDoc&&) noexcept;
  ~SceneDoc();

  // User overrides. apply: "key.path=value" as on the command line (--set); apply_file: an overrides file
  // as `pastemix sweep` writes it (`key.path = value` lines, '#' comments), each line its own origin.
  void apply(const std::string& assignment);
  void apply_file(const std::filesystem::path& overrides);
  void set(const std::string& path, const std::string& value_literal);

  // Edits of the studies, typed (no text round trip): a number key gets a float value; a new number key in
  // an existing table; a key or an array element removed.
  void set_number(const std::string& path, double value);
  void add_number(const std::string& table_path, const std::string& key, double value);
  void erase(const std::string& path);

  // Queries. get: the value as TOML text; string/number: typed (InputError if absent or of another type);
  // size: elements of an array (0 if absent); line_of: the line of the key in the scene file (0 if edited).
  bool has(const std::string& path) const;
  std::string get(const std::string& path) const;
  std::string string(const std::string& path) const;
  double number(const std::string& path) const;
  std::size_t size(const std::string& path) const;
  int line_of(const std::string& path) const;

  const std::string& path() const { return path_; }
  bool edited() const { return !edits_.empty(); }
  std::string text() const;
  Scene load() const;

  struct Tree;  // the parsed document and the notes of --set values (scene_doc.cpp)

 private:
  SceneDoc() = default;
  void set_from(const std::string& path, const std::string& literal, const std::optional<EditOrigin>& from,
                const std::string& note);
  void record(const std::string& path, const std::string& literal, const EditOrigin& at, const std::string& note);
  void add_from(const std::string& path, const std::string& literal, const EditOrigin& at, const std::string& in_scene,
                const std::string& note);
  void edit(std::function<void(Tree&)> change);
  const Tree& tree() const { return *tree_; }
  std::string path_;
  std::string text_;  // the file as read
  // Every edit, replayed on a fresh parse when a tree shared with a copy is edited: a toml++ node copy drops
  // its source line, and the lines are what the errors name.
  std::vector<std::function<void(Tree&)>> edits_;
  std::shared_ptr<Tree> tree_;
};

// The scene with the overrides file (if not empty) and then each --set applied: the order of `pastemix run`,
// `sweep` and `calibrate`.
SceneDoc scene_with_overrides(const std::filesystem::path& scene, const std::filesystem::path& overrides_file,
                              const std::vector<std::string>& sets);

// load_scene with --set style overrides applied in order ("key.path=value").
Scene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides);

}  // namespace pastemix::model
