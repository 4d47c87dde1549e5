// SPDX-License-Identifier: MIT
#include "base/params.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "base/error.h"
#include "base/range.h"
#include "base/suggest.h"

namespace pastemix {

struct Params::State {
  std::shared_ptr<const toml::table> root;  // keeps the parsed document alive
  std::shared_ptr<const Notes> notes;       // may be null
  const toml::table* table = nullptr;
  std::string path;
  int line = 0;
  mutable std::set<std::string, std::less<>> used;
  // Every key a consumer asked for, present or not: the names a misspelt key is compared with.
  mutable std::set<std::string, std::less<>> asked;
  mutable std::vector<std::shared_ptr<State>> children;
};

Params::Params(std::shared_ptr<State> state) : state_(std::move(state)) {}
Params::Params(const Params&) = default;
Params& Params::operator=(const Params&) = default;
Params::Params(Params&&) noexcept = default;
Params& Params::operator=(Params&&) noexcept = default;
Params::~Params() = default;

Params Params::parse(std::string_view text, std::string display_path) {
  auto state = std::make_shared<State>();
  state->path = std::move(display_path);
  try {
    state->root = std::make_shared<toml::table>(toml::parse(text, state->path));
  } catch (const toml::parse_error& e) {
    throw InputError(state->path, static_cast<int>(e.source().begin.line), "",
                     fmt::format("TOML syntax error: {}", e.description()));
  }
  state->table = state->root.get();
  state->line = 1;
  return Params(std::move(state));
}

Params Params::from_table(std::shared_ptr<const toml::table> root, std::string display_path,
                          std::shared_ptr<const Notes> notes) {
  auto state = std::make_shared<State>();
  state->path = std::move(display_path);
  state->root = std::move(root);
  state->notes = std::move(notes);
  state->table = state->root.get();
  state->line = 1;
  return Params(std::move(state));
}

Params Params::parse_file(const std::filesystem::path& path) {
  if (std::filesystem::is_directory(path)) throw InputError(path.string(), 0, "", "is a folder, not a TOML file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "", "cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse(buffer.str(), path.string());
}

const std::string& Params::path() const { return state_->path; }
int Params::line() const { return state_->line; }

int Params::line_of(std::string_view key) const {
  const toml::node* n = state_->table->get(key);
  return n ? static_cast<int>(n->source().begin.line) : 0;
}

// The file a node was read from: its own source (an edit may have brought it from an overrides file), or
// this table's.
static const std::string& file_of(const toml::node& n, const std::string& fallback) {
  return n.source().path && !n.source().path->empty() ? *n.source().path : fallback;
}

static std::string field_of(std::string_view key, const toml::node* n, const Params::Notes* notes) {
  std::string field = fmt::format("key '{}'", key);
  if (n && notes)
    if (auto it = notes->find(n); it != notes->end()) field += " " + it->second;
  return field;
}

void Params::fail(std::string_view key, const std::string& message) const {
  const toml::node* n = state_->table->get(key);
  const int line = n ? static_cast<int>(n->source().begin.line) : 0;
  throw InputError(line && n ? file_of(*n, state_->path) : state_->path, line ? line : state_->line,
                   field_of(key, n, state_->notes.get()), message);
}

bool Params::has(std::string_view key) const {
  state_->asked.emplace(key);
  return state_->table->contains(key);
}

std::vector<std::string> Params::keys() const {
  std::vector<std::string> out;
  for (auto&& [k, v] : *state_->table) out.emplace_back(k.str());
  return out;
}

const toml::node* Params::get(std::string_view key) const {
  const toml::node* n = state_->table->get(key);
  state_->asked.emplace(key);
  if (n) state_->used.emplace(key);
  return n;
}

std::optional<double> Params::optional_number(std::string_view key, Range range) const {
  const toml::node* n = get(key);
  if (!n) return std::nullopt;
  double v;
  if (auto f = n->as_floating_point()) v = f->get();
  else if (auto i = n->as_integer()) v = static_cast<double>(i->get());
  else fail(key, fmt::format("expected {}, got a value that is not a number", range_words(range)));
  if (!(std::isfinite(v) && in_range(v, range))) fail(key, fmt::format("expected {}, got {}", range_words(range), v));
  return v;
}

double Params::number(std::string_view key, Range range) const {
  auto v = optional_number(key, range);
  if (!v) fail(key, fmt::format("required key is missing (expected {})", range_words(range)));
  return *v;
}

double Params::number_or(std::string_view key, double fallback, Range range) const {
  return optional_number(key, range).value_or(fallback);
}

long Params::integer(std::string_view key) const {
  const toml::node* n = get(key);
  if (!n) fail(key, "required key is missing (expected an integer)");
  auto i = n->as_integer();
  if (!i) fail(key, "expected an integer");
  return static_cast<long>(i->get());
}

long Params::integer_or(std::string_view key, long fallback) const { return has(key) ? integer(key) : fallback; }

std::string Params::string(std::string_view key) const {
  const toml::node* n = get(key);
  if (!n) fail(key, "required key is missing (expected a string)");
  auto s = n->as_string();
  if (!s) fail(key, "expected a string");
  return s->get();
}

std::string Params::string_or(std::string_view key, std::string fallback) const {
  return has(key) ? string(key) : fallback;
}

std::string Params::choice(std::string_view key, const std::vector<std::string>& choices) const {
  std::string s = string(key);
  if (std::find(choices.begin(), choices.end(), s) == choices.end())
    fail(key, fmt::format("'{}' is not one of: {}", s, fmt::join(choices, ", ")));
  return s;
}

std::string Params::choice_or(std::string_view key, const std::vector<std::string>& choices,
                              std::string fallback) const {
  return has(key) ? choice(key, choices) : fallback;
}

bool Params::boolean_or(std::string_view key, bool fallback) const {
  const toml::node* n = get(key);
  if (!n) return fallback;
  auto b = n->as_boolean();
  if (!b) fail(key, "expected true or false");
  return b->get();
}

std::optional<std::vector<double>> Params::optional_numbers(std::string_view key, std::size_t expected_size) const {
  const toml::node* n = get(key);
  if (!n) return std::nullopt;
  auto arr = n->as_array();
  if (!arr) fail(key, "expected an array of numbers");
  std::vector<double> out;
  for (auto&& el : *arr) {
    if (auto f = el.as_floating_point()) out.push_back(f->get());
    else if (auto i = el.as_integer()) out.push_back(static_cast<double>(i->get()));
    else fail(key, "expected an array of numbers");
    if (!std::isfinite(out.back())) fail(key, "array holds a non-finite number");
  }
  if (expected_size && out.size() != expected_size)
    fail(key, fmt::format("expected {} numbers, got {}", expected_size, out.size()));
  return out;
}

std::vector<double> Params::numbers(std::string_view key, std::size_t expected_size) const {
  auto v = optional_numbers(key, expected_size);
  if (!v) fail(key, "required key is missing (expected an array of numbers)");
  return *v;
}

std::shared_ptr<Params::State> Params::child_state(const toml::table* t) const {
  auto child = std::make_shared<State>();
  child->root = state_->root;
  child->notes = state_->notes;
  child->table = t;
  const int line = static_cast<int>(t->source().begin.line);
  child->line = line ? line : state_->line;  // a table an edit added without a source: its parent's line
  child->path = line ? file_of(*t, state_->path) : state_->path;
  state_->children.push_back(child);
  return child;
}

std::optional<Params> Params::optional_table(std::string_view key) const {
  const toml::node* n = get(key);
  if (!n) return std::nullopt;
  auto t = n->as_table();
  if (!t) fail(key, "expected a table");
  return Params(child_state(t));
}

Params Params::table(std::string_view key) const {
  auto t = optional_table(key);
  if (!t) fail(key, "required table is missing");
  return *t;
}

std::vector<Params> Params::tables(std::string_view key) const {
  std::vector<Params> out;
  const toml::node* n = get(key);
  if (!n) return out;
  auto arr = n->as_array();
  if (!arr) fail(key, "expected an array of tables ([[" + std::string(key) + "]])");
  for (auto&& el : *arr) {
    auto t = el.as_table();
    if (!t) fail(key, "expected an array of tables");
    out.push_back(Params(child_state(t)));
  }
  return out;
}

void Params::ignore(std::string_view key) const { state_->used.emplace(key); }

void Params::finish() const {
  for (auto&& [k, v] : *state_->table) {
    if (!state_->used.count(k.str())) {
      const std::vector<std::string> known(state_->asked.begin(), state_->asked.end());
      throw InputError(file_of(v, state_->path), static_cast<int>(v.source().begin.line),
                       field_of(shown(k.str()), &v, state_->notes.get()),
                       fmt::format("unknown key{} (nothing reads it; check the spelling and the table it is in)",
                                   did_you_mean(k.str(), known)));
    }
  }
  for (const auto& child : state_->children) Params(child).finish();
}

}  // namespace pastemix
