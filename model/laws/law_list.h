// SPDX-License-Identifier: MIT
// LawList: a typed, checked-in list of laws (STYLE 5.2; LAMMPS's register table made typed). Each law is one
// struct that carries its scene name (`name`), its per-material-pair `Params` (with `using Law = ...` so
// that a visitor of a table can name the law) and its kernels; the list gives the scene names, the
// variant of per-pair parameter tables the engine holds, and the empty table of a law found by name.
#pragma once

#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace pastemix::model {

template <class... Laws>
struct LawList {
  // Per-material-pair parameter tables (n_materials^2, row-major), one alternative per law.
  using Table = std::variant<std::vector<typename Laws::Params>...>;
  // One law's parameters (a drag law: one per fluid region).
  using One = std::variant<typename Laws::Params...>;

  // Scene names, in list order.
  static std::vector<std::string> names() { return {std::string(Laws::name)...}; }

  // The empty table of the law named `name` (one of names(); the scene checked it).
  static Table table_of(const std::string& name) {
    Table t;
    ((name == Laws::name ? (t.template emplace<std::vector<typename Laws::Params>>(), true) : false) || ...);
    return t;
  }

  // Calls f(std::type_identity<Law>{}) for the law named `name` (nothing if none is).
  template <class F>
  static void with(const std::string& name, F&& f) {
    ((name == Laws::name ? (f(std::type_identity<Laws>{}), true) : false) || ...);
  }

  // Whether `name` is one of names().
  static bool has(const std::string& name) { return ((name == Laws::name) || ...); }

  // The largest history (doubles per contact) of any law in the list.
  static constexpr int max_history() {
    int m = 0;
    ((m = Laws::history_size > m ? Laws::history_size : m), ...);
    return m;
  }
};

// The law of a table (a visitor's argument): `LawOf<decltype(table)>`.
template <class TableVector>
using LawOf = typename std::decay_t<TableVector>::value_type::Law;

// The scene name of the law whose table `t` holds.
template <class Table>
std::string law_name(const Table& t) {
  return std::visit([](const auto& v) { return std::string(LawOf<decltype(v)>::name); }, t);
}

}  // namespace pastemix::model
