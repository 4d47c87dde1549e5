// SPDX-License-Identifier: MIT
#include "model/scene_doc.h"

#include <charconv>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "base/error.h"
#include "base/params.h"
#include "model/scene/read.h"

namespace pastemix::model {

struct SceneDoc::Tree {
  toml::table root;
  Params::Notes notes;  // "(--set k=v)" after the key of each value --set wrote
};

namespace {

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> out(1);
  for (char c : path) {
    if (c == '.') out.emplace_back();
    else out.back() += c;
  }
  return out;
}

int line_of_node(const toml::node* n) { return n ? static_cast<int>(n->source().begin.line) : 0; }

bool is_index(const std::string& seg, std::size_t* idx) {
  const auto [p, ec] = std::from_chars(seg.data(), seg.data() + seg.size(), *idx);
  return ec == std::errc() && p == seg.data() + seg.size();
}

// One step down: a table key, an array index, or the element of an array of tables whose `name` (or
// `materials`, for interactions) is seg.
toml::node* child(toml::node* cur, const std::string& seg) {
  if (auto* t = cur->as_table()) return t->get(seg);
  auto* a = cur->as_array();
  if (!a) return nullptr;
  std::size_t idx = 0;
  if (is_index(seg, &idx)) return idx < a->size() ? a->get(idx) : nullptr;
  for (auto& el : *a)
    if (auto* et = el.as_table())
      for (const char* k : {"name", "materials"})
        if (auto v = (*et)[k].value<std::string>(); v && *v == seg) return &el;
  return nullptr;
}

// Walks `path`; returns the node or nullptr, and the deepest node reached (for the error line).
toml::node* walk(toml::table& root, const std::string& path, const toml::node** deepest) {
  toml::node* cur = &root;
  *deepest = &root;
  for (const std::string& seg : split_path(path)) {
    if (seg.empty()) return nullptr;
    cur = child(cur, seg);
    if (!cur) return nullptr;
    *deepest = cur;
  }
  return cur;
}

toml::node* walk(const toml::table& root, const std::string& path, const toml::node** deepest) {
  return walk(const_cast<toml::table&>(root), path, deepest);  // read-only walk: the same steps
}

const char* type_name(toml::node_type t) {
  switch (t) {
    case toml::node_type::table: return "table";
    case toml::node_type::array: return "array";
    case toml::node_type::string: return "string";
    case toml::node_type::integer: return "integer";
    case toml::node_type::floating_point: return "float";
    case toml::node_type::boolean: return "boolean";
    default: return "date/time";
  }
}

std::string article(const std::string& noun) {
  return (std::string("aeiou").find(noun[0]) != std::string::npos ? "an " : "a ") + noun;
}

toml::table parse_tree(const std::string& text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(path, static_cast<int>(e.source().begin.line), "",
                     std::string("TOML syntax error: ") + std::string(e.description()));
  }
}

// A literal parsed so that its node's source is `at` (file and line): errors about the value name the place
// the user wrote it. nullptr if the literal is no TOML value.
std::unique_ptr<toml::table> parse_literal(const std::string& literal, const EditOrigin& at) {
  std::string text(at.line > 1 ? static_cast<std::size_t>(at.line - 1) : 0, '\n');
  text += "v = " + literal;
  try {
    return std::make_unique<toml::table>(toml::parse(text, at.file));
  } catch (const toml::parse_error&) {
    return nullptr;
  }
}

template <class T>
std::string toml_text(const T& value) {
  std::ostringstream os;
  os << toml::value<T>(value);
  return os.str();
}

// Replaces the node at `path` (its owner a table or an array) by `value`, moved so that its source is kept.
void replace(toml::table& root, const std::string& path, toml::node&& value) {
  const auto dot = path.rfind('.');
  const std::string last = dot == std::string::npos ? path : path.substr(dot + 1);
  const toml::node* deepest = nullptr;
  toml::node* owner = dot == std::string::npos ? &root : walk(root, path.substr(0, dot), &deepest);
  value.visit([&](auto& x) {
    using V = std::remove_reference_t<decltype(x)>;
    if (auto* t = owner->as_table()) {
      t->insert_or_assign(last, std::move(x));
    } else if (auto* a = owner->as_array()) {
      toml::node* here = child(owner, last);
      std::size_t at = 0;
      while (a->get(at) != here) ++at;
      const auto it = a->cbegin() + static_cast<std::ptrdiff_t>(at);
      a->insert(a->erase(it), V(std::move(x)));
    }
  });
}

}  // namespace

SceneDoc SceneDoc::parse(std::string text, std::string display_path) {
  SceneDoc d;
  d.path_ = std::move(display_path);
  d.text_ = std::move(text);
  d.tree_ = std::make_shared<Tree>();
  d.tree_->root = parse_tree(d.text_, d.path_);
  return d;
}

SceneDoc SceneDoc::parse_file(const std::filesystem::path& path) {
  if (std::filesystem::is_directory(path)) throw InputError(path.string(), 0, "", "is a folder, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "", "cannot open the scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path.string());
}

SceneDoc::SceneDoc(const SceneDoc&) = default;
SceneDoc& SceneDoc::operator=(const SceneDoc&) = default;
SceneDoc::SceneDoc(SceneDoc&&) noexcept = default;
SceneDoc& SceneDoc::operator=(SceneDoc&&) noexcept = default;
SceneDoc::~SceneDoc() = default;

void SceneDoc::edit(std::function<void(Tree&)> change) {
  if (tree_.use_count() > 1) {  // shared with a copy: rebuild from the text, sources and all
    auto fresh = std::make_shared<Tree>();
    fresh->root = parse_tree(text_, path_);
    for (const auto& e : edits_) e(*fresh);
    tree_ = std::move(fresh);
  }
  change(*tree_);
  edits_.push_back(std::move(change));
}

void SceneDoc::apply(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(path_, 0, assignment, "an override is key.path=value");
  set_from(assignment.substr(0, eq), assignment.substr(eq + 1), std::nullopt, "(--set " + assignment + ")");
}

void SceneDoc::apply_file(const std::filesystem::path& overrides) {
  std::ifstream in(overrides);
  if (!in) throw InputError(overrides.string(), 0, "", "cannot open the override file");
  auto trim = [](const std::string& s) {
    const auto a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
  };
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const auto eq = t.find('=');
    const std::string key = eq == std::string::npos ? "" : trim(t.substr(0, eq));
    const std::string value = eq == std::string::npos ? "" : trim(t.substr(eq + 1));
    if (key.empty() || value.empty()) throw InputError(overrides.string(), n, key, "expected key.path = value");
    set_from(key, value, EditOrigin{overrides.string(), n, ""}, "");
  }
}

void SceneDoc::set(const std::string& path, const std::string& value_literal) {
  set_from(path, value_literal, std::nullopt, "");
}

// Checks a user override against the document (the path exists, the type matches) and records it. Errors
// name `from` (an overrides file and line) or, without it, the scene file at the key (or the deepest table
// found); the new node's source is the same place.
void SceneDoc::set_from(const std::string& path, const std::string& literal, const std::optional<EditOrigin>& from,
                        const std::string& note) {
  const toml::node* deepest = nullptr;
  const toml::node* n = walk(tree_->root, path, &deepest);
  const EditOrigin at = from ? *from : EditOrigin{path_, line_of_node(n ? n : deepest), ""};
  const std::string in_scene = from ? fmt::format(" (in the scene {})", path_) : "";
  if (!n) return add_from(path, literal, at, in_scene, note);
  const auto want = n->type();
  if (want == toml::node_type::table) throw InputError(at.file, at.line, path, "is a table; override its keys one by one");
  std::string text = literal;
  std::unique_ptr<toml::table> parsed = parse_literal(text, at);
  if (!parsed && n->is_string()) parsed = parse_literal(text = toml_text(literal), at);  // a bare word
  if (!parsed) throw InputError(at.file, at.line, path, "'" + literal + "' is not a TOML value");
  const auto got = parsed->get("v")->type();
  if (want == toml::node_type::floating_point && got == toml::node_type::integer)
    text = toml_text(static_cast<double>(parsed->get("v")->as_integer()->get()));
  else if (want != got)
    throw InputError(at.file, at.line, path,
                     "expects " + article(type_name(want)) + ", got " + article(type_name(got)) + " ('" + literal +
                         "')" + in_scene);
  record(path, text, at, note);
}

// An override of a key the scene does not have adds it, to a table the scene has (an array element or the
// table itself must exist: `fluid.0.dynamics` adds to the first [[fluid]], `fluid.3.x` with one region is an
// error). There is no type to check against; the scene reader checks the key and its value (an unknown or
// misspelled key is an error at `at`, the overrides file's line), so the shipped flow variant of the mixing
// scenes (datasets/scenes/mixing_flow.overrides.toml) needs no edit of their files, whose text the studies'
// run caches are keyed by (scene_hash).
void SceneDoc::add_from(const std::string& path, const std::string& literal, const EditOrigin& at,
                        const std::string& in_scene, const std::string& note) {
  const auto dot = path.rfind('.');
  const std::string owner = dot == std::string::npos ? "" : path.substr(0, dot), key = path.substr(dot + 1);
  const toml::node* deepest = nullptr;
  const toml::node* table = owner.empty() ? &tree_->root : walk(tree_->root, owner, &deepest);
  if (table == nullptr || !table->is_table() || key.empty() || std::isdigit(static_cast<unsigned char>(key[0])))
    throw InputError(at.file, at.line, path,
                     "unknown key path (an override replaces a key of the scene or adds one to a table it has)" + in_scene);
  if (!parse_literal(literal, at))
    throw InputError(at.file, at.line, path, "'" + literal + "' is not a TOML value (a new key takes no bare word)");
  record(path, literal, at, note);
}

// The edit itself, replayable: the literal is parsed anew each time (a moved node keeps its source).
void SceneDoc::record(const std::string& path, const std::string& literal, const EditOrigin& at,
                      const std::string& note) {
  edit([path, literal, at, note](Tree& t) {
    replace(t.root, path, std::move(*parse_literal(literal, at)->get("v")));
    if (!note.empty()) {
      const toml::node* d = nullptr;
      t.notes[walk(t.root, path, &d)] = note;
    }
  });
}

void SceneDoc::set_number(const std::string& path, double value) {
  const toml::node* deepest = nullptr;
  const toml::node* n = walk(tree_->root, path, &deepest);
  if (!n || !(n->is_floating_point() || n->is_integer()))
    throw InputError(path_, line_of_node(n ? n : deepest), path, "no number at this path in the scene");
  record(path, toml_text(value), EditOrigin{path_, line_of_node(n), ""}, "");
}

void SceneDoc::add_number(const std::string& table_path, const std::string& key, double value) {
  const toml::node* deepest = nullptr;
  const toml::node* n = walk(tree_->root, table_path, &deepest);
  if (!n || !n->is_table()) throw InputError(path_, line_of_node(n ? n : deepest), table_path, "no such table in the scene");
  if (n->as_table()->contains(key)) throw InputError(path_, line_of_node(n), table_path + "." + key, "the key exists");
  const EditOrigin at{path_, line_of_node(n), ""};
  const std::string literal = toml_text(value);
  edit([table_path, key, literal, at](Tree& t) {
    const toml::node* d = nullptr;
    walk(t.root, table_path, &d)->as_table()->insert(key, std::move(*parse_literal(literal, at)->get("v")->as_floating_point()));
  });
}

void SceneDoc::erase(const std::string& path) {
  const toml::node* deepest = nullptr;
  if (!walk(tree_->root, path, &deepest)) throw InputError(path_, line_of_node(deepest), path, "no such key in the scene");
  edit([path](Tree& t) {
    const auto dot = path.rfind('.');
    const std::string last = dot == std::string::npos ? path : path.substr(dot + 1);
    const toml::node* d = nullptr;
    toml::node* owner = dot == std::string::npos ? &t.root : walk(t.root, path.substr(0, dot), &d);
    toml::node* here = child(owner, last);
    if (auto* tab = owner->as_table()) {
      tab->erase(last);
    } else if (auto* a = owner->as_array()) {
      std::size_t at = 0;
      while (a->get(at) != here) ++at;
      a->erase(a->cbegin() + static_cast<std::ptrdiff_t>(at));
    }
  });
}

bool SceneDoc::has(const std::string& path) const {
  const toml::node* deepest = nullptr;
  return walk(tree().root, path, &deepest) != nullptr;
}

std::string SceneDoc::get(const std::string& path) const {
  const toml::node* deepest = nullptr;
  const toml::node* n = walk(tree().root, path, &deepest);
  if (!n) throw InputError(path_, line_of_node(deepest), path, "no such key in the scene");
  std::ostringstream os;
  n->visit([&](auto& v) { os << v; });
  return os.str();
}

std::string SceneDoc::string(const std::string& path) const {
  const toml::node* deepest = nullptr;
  const toml::node* n = walk(tree().root, path, &deepest);
  if (!n || !n->is_string()) throw InputError(path_, line_of_node(n ? n : deepest), path, "expected a string here");
  return n->as_string()->get();
}

double SceneDoc::number(const std::string& path) const {
  const toml::node* deepest = nullptr;
  const toml::node* n = walk(tree().root, path, &deepest);
  if (auto v = n ? n->value<double>() : std::nullopt) return *v;  // an integer reads as its double
  throw InputError(path_, line_of_node(n ? n : deepest), path, "expected a number here");
}

std::size_t SceneDoc::size(const std::string& path) const {
  const toml::node* deepest = nullptr;
  const toml::node* n = walk(tree().root, path, &deepest);
  return n && n->is_array() ? n->as_array()->size() : 0;
}

int SceneDoc::line_of(const std::string& path) const {
  const toml::node* deepest = nullptr;
  return line_of_node(walk(tree().root, path, &deepest));
}

std::string SceneDoc::text() const {
  if (edits_.empty()) return text_;
  std::ostringstream os;
  os << toml::toml_formatter(tree().root, toml::toml_formatter::default_flags & ~toml::format_flags::indentation);
  return os.str();
}

Scene SceneDoc::load() const {
  // The Params share the tree (and its notes); the scene keeps nothing of them.
  const std::shared_ptr<const toml::table> root(tree_, &tree_->root);
  const std::shared_ptr<const Params::Notes> notes(tree_, &tree_->notes);
  return read_scene(Params::from_table(root, path_, notes), text());
}

SceneDoc scene_with_overrides(const std::filesystem::path& scene, const std::filesystem::path& overrides_file,
                              const std::vector<std::string>& sets) {
  SceneDoc d = SceneDoc::parse_file(scene);
  if (!overrides_file.empty()) d.apply_file(overrides_file);
  for (const auto& a : sets) d.apply(a);
  return d;
}

Scene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  return scene_with_overrides(path, {}, overrides).load();
}

}  // namespace pastemix::model
