// SPDX-License-Identifier: MIT
// Params: a TOML table that remembers which keys were read.
//
// Scenes and manifests are read through Params so that a key nothing reads (a typo, a misplaced option) is
// an error with file:line, as pbrt's ParameterDictionary::ReportUnused does. Each consumer reads its keys
// (the only place those names appear) and the loader calls finish() once at the end.
//
//   Params p = Params::parse_file("scene.toml");
//   double dt = p.number("time_step", Range::positive);   // required
//   int seed = p.integer_or("seed", 1);                   // optional with default
//   for (Params& m : p.tables("material")) { ... m.finish(); }
//   p.finish();  // throws InputError "scene.toml:12: key 'tme_step': unknown key" if one was never read
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/csv.h"  // Range

namespace toml {
inline namespace v3 {
class table;
class node;
}  // namespace v3
}  // namespace toml

namespace pastemix {

class Params {
 public:
  static Params parse_file(const std::filesystem::path& path);
  static Params parse(std::string_view text, std::string display_path);
  // A note shown after a key in error messages (e.g. "(--set time_step=1e-6)": where the value came from).
  using Notes = std::map<const toml::node*, std::string>;
  // A document parsed (and possibly edited) elsewhere, read in place (model/scene_doc.h). Errors name each
  // value's own source (file and line), which an edit may have set to an overrides file; `display_path` is
  // for keys without one.
  static Params from_table(std::shared_ptr<const toml::table> root, std::string display_path,
                           std::shared_ptr<const Notes> notes = {});

  Params(const Params&);
  Params& operator=(const Params&);
  Params(Params&&) noexcept;
  Params& operator=(Params&&) noexcept;
  ~Params();

  const std::string& path() const;
  // Line of this table's header (or of the key that holds it); 0 if unknown.
  int line() const;
  // Line of a key in this table; 0 if absent.
  int line_of(std::string_view key) const;
  // "path:line: key 'name'" prefix pieces for messages about a value that parsed but makes no sense.
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

  bool has(std::string_view key) const;
  std::vector<std::string> keys() const;

  double number(std::string_view key, Range range = Range::any) const;
  double number_or(std::string_view key, double fallback, Range range = Range::any) const;
  std::optional<double> optional_number(std::string_view key, Range range = Range::any) const;
  long integer(std::string_view key) const;
  long integer_or(std::string_view key, long fallback) const;
  std::string string(std::string_view key) const;
  std::string string_or(std::string_view key, std::string fallback) const;
  // A string that must be one of `choices` (error lists them).
  std::string choice(std::string_view key, const std::vector<std::string>& choices) const;
  std::string choice_or(std::string_view key, const std::vector<std::string>& choices, std::string fallback) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  // An array of numbers (e.g. a 3-vector); `expected_size` 0 means any size.
  std::vector<double> numbers(std::string_view key, std::size_t expected_size = 0) const;
  std::optional<std::vector<double>> optional_numbers(std::string_view key, std::size_t expected_size = 0) const;

  // Sub-table; required / optional. Reading it marks the key used; its own keys are checked by finish().
  Params table(std::string_view key) const;
  std::optional<Params> optional_table(std::string_view key) const;
  // An array of tables ([[material]]); empty if the key is absent.
  std::vector<Params> tables(std::string_view key) const;

  // Throws InputError at the first key (here or in any sub-table obtained from this one) that was never read.
  void finish() const;
  // Marks a key as read without using it (for keys handled elsewhere, e.g. documentation fields).
  void ignore(std::string_view key) const;

 private:
  struct State;
  explicit Params(std::shared_ptr<State> state);
  std::shared_ptr<State> child_state(const toml::table* t) const;
  const toml::node* get(std::string_view key) const;
  std::shared_ptr<State> state_;
};

}  // namespace pastemix
