// SPDX-License-Identifier: MIT
#include "model/scene_override.h"

#include <charconv>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "base/error.h"

namespace pastemix::model {
namespace {

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : path) {
    if (c == '.') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

int line_of(const toml::node* n) { return n ? static_cast<int>(n->source().begin.line) : 0; }

// Walks `path`; returns the node or nullptr, and the deepest node reached (for the error line).
toml::node* walk(toml::table& root, const std::string& path, const toml::node** deepest) {
  toml::node* cur = &root;
  *deepest = &root;
  for (const std::string& seg : split_path(path)) {
    if (seg.empty()) return nullptr;
    toml::node* next = nullptr;
    if (auto* t = cur->as_table()) {
      next = t->get(seg);
    } else if (auto* a = cur->as_array()) {
      std::size_t idx = 0;
      const auto [p, ec] = std::from_chars(seg.data(), seg.data() + seg.size(), idx);
      if (ec == std::errc() && p == seg.data() + seg.size()) {
        if (idx < a->size()) next = a->get(idx);
      } else {
        // An array of tables: the element whose `name` (or `materials`, for interactions) is seg.
        for (auto& el : *a) {
          auto* et = el.as_table();
          if (!et) continue;
          for (const char* k : {"name", "materials"})
            if (auto v = (*et)[k].value<std::string>(); v && *v == seg) next = &el;
          if (next) break;
        }
      }
    }
    if (!next) return nullptr;
    cur = next;
    *deepest = cur;
  }
  return cur;
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

}  // namespace

SceneDoc SceneDoc::parse(const std::string& text, const std::string& display_path) {
  SceneDoc d;
  d.path_ = display_path;
  try {
    d.root_ = std::make_unique<toml::table>(toml::parse(text, display_path));
  } catch (const toml::parse_error& e) {
    throw InputError(display_path, static_cast<int>(e.source().begin.line), "", std::string(e.description()));
  }
  return d;
}

SceneDoc SceneDoc::parse_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), 0, "", "cannot open the scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path.string());
}

SceneDoc::SceneDoc(const SceneDoc& o) : path_(o.path_), root_(std::make_unique<toml::table>(*o.root_)) {}
SceneDoc& SceneDoc::operator=(const SceneDoc& o) {
  path_ = o.path_;
  root_ = std::make_unique<toml::table>(*o.root_);
  return *this;
}
SceneDoc::~SceneDoc() = default;

void SceneDoc::apply(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(path_, 0, assignment, "an override is key.path=value");
  set(assignment.substr(0, eq), assignment.substr(eq + 1));
}

bool SceneDoc::has(const std::string& path) const {
  const toml::node* deepest = nullptr;
  return walk(*root_, path, &deepest) != nullptr;
}

std::string SceneDoc::get(const std::string& path) const {
  const toml::node* deepest = nullptr;
  toml::node* n = walk(*root_, path, &deepest);
  if (!n) throw InputError(path_, line_of(deepest), path, "no such key in the scene");
  std::ostringstream os;
  n->visit([&](auto& v) { os << v; });
  return os.str();
}

void SceneDoc::set(const std::string& path, const std::string& value_literal) {
  const toml::node* deepest = nullptr;
  toml::node* n = walk(*root_, path, &deepest);
  if (!n)
    throw InputError(path_, line_of(deepest), path,
                     "unknown key path (overrides only replace keys the scene already has)");
  const int line = line_of(n);
  toml::table parsed;
  bool ok = true;
  try {
    parsed = toml::parse("v = " + value_literal);
  } catch (const toml::parse_error&) {
    ok = false;
  }
  toml::node* v = ok ? parsed.get("v") : nullptr;
  toml::table bare;  // a bare word for a string key
  if (!v && n->is_string()) {
    bare.insert("v", value_literal);
    v = bare.get("v");
  }
  if (!v) throw InputError(path_, line, path, "'" + value_literal + "' is not a TOML value");
  const auto want = n->type(), got = v->type();
  if (want == toml::node_type::table)
    throw InputError(path_, line, path, "is a table; override its keys one by one");
  // Replace in place: the node's owner is a table or an array; walk to the parent.
  const std::string parent = path.rfind('.') == std::string::npos ? "" : path.substr(0, path.rfind('.'));
  const std::string last = path.substr(path.rfind('.') == std::string::npos ? 0 : path.rfind('.') + 1);
  toml::node* owner = &*root_;
  if (!parent.empty()) owner = walk(*root_, parent, &deepest);
  auto put = [&](auto&& value) {
    if (auto* t = owner->as_table()) {
      t->insert_or_assign(last, std::forward<decltype(value)>(value));
    } else if (auto* a = owner->as_array()) {
      std::size_t idx = 0;
      std::from_chars(last.data(), last.data() + last.size(), idx);
      const auto at = static_cast<std::ptrdiff_t>(idx);
      a->erase(a->cbegin() + at);
      a->insert(a->cbegin() + at, std::forward<decltype(value)>(value));
    }
  };
  if (want == got) {
    v->visit([&](auto& x) { put(x); });
  } else if (want == toml::node_type::floating_point && got == toml::node_type::integer) {
    put(static_cast<double>(v->as_integer()->get()));
  } else {
    throw InputError(path_, line, path,
                     "expects " + article(type_name(want)) + ", got " + article(type_name(got)) + " ('" +
                         value_literal + "')");
  }
}

std::string SceneDoc::text() const {
  std::ostringstream os;
  os << toml::toml_formatter(*root_, toml::toml_formatter::default_flags & ~toml::format_flags::indentation);
  return os.str();
}

Scene SceneDoc::load() const { return parse_scene(text(), path_); }

std::vector<std::string> read_override_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), 0, "", "cannot open the override file");
  std::vector<std::string> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos) throw InputError(path.string(), n, "", "expected key.path = value");
    auto trim = [](std::string s) {
      const auto a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t\r");
      return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
    };
    const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
    if (key.empty() || value.empty()) throw InputError(path.string(), n, key, "expected key.path = value");
    out.push_back(key + "=" + value);
  }
  return out;
}

Scene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  if (overrides.empty()) return load_scene(path);
  SceneDoc d = SceneDoc::parse_file(path);
  for (const auto& o : overrides) d.apply(o);
  return d.load();
}

}  // namespace pastemix::model
