// SPDX-License-Identifier: MIT
#include "lab/drag/settling.h"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "base/csv.h"
#include "base/error.h"
#include "base/units.h"

namespace pastemix::lab::drag {

namespace {

const Suspension& find_suspension(const CsvTable& t, const CsvTable::Row& row, int id,
                                  const std::vector<Suspension>& suspensions) {
  for (const auto& s : suspensions)
    if (s.id == id) return s;
  t.fail(row, "suspension", fmt::format("unknown suspension id {} (not in the suspensions file)", id));
}

int positive_id(const CsvTable& t, const CsvTable::Row& row, std::string_view column) {
  const long id = t.integer(row, column);
  if (id <= 0 || id > 1'000'000) t.fail(row, column, fmt::format("expected a positive id, got {}", id));
  return static_cast<int>(id);
}

// The file, with exactly these columns (any order): a missing or an unknown column is an input error.
CsvTable read_exact(const std::filesystem::path& path, const std::vector<std::string>& cols) {
  auto t = CsvTable::read(path);
  t.require_columns(cols);
  t.require_only_columns(cols);
  return t;
}

}  // namespace

std::vector<Suspension> read_suspensions(const std::filesystem::path& path) {
  const auto t = read_exact(path, {"suspension", "density_kg_m3", "plastic_viscosity_Pa_s", "yield_stress_Pa"});
  std::vector<Suspension> out;
  for (const auto& row : t.rows()) {
    Suspension s;
    s.id = positive_id(t, row, "suspension");
    s.line = row.line;
    s.rho_f = t.number(row, "density_kg_m3", Range::positive);
    s.eta_B = t.number(row, "plastic_viscosity_Pa_s", Range::positive);
    s.tau_y = t.number(row, "yield_stress_Pa", Range::non_negative);
    for (const auto& o : out)
      if (o.id == s.id) t.fail(row, "suspension", fmt::format("duplicate suspension id {} (line {})", s.id, o.line));
    out.push_back(s);
  }
  return out;
}

SettlingData read_settling_data(const std::filesystem::path& spheres, const std::filesystem::path& suspensions) {
  SettlingData data;
  data.spheres_file = spheres.string();
  data.suspensions_file = suspensions.string();
  data.suspensions = read_suspensions(suspensions);
  const auto t = read_exact(spheres, {"row_id", "suspension", "diameter_m", "sphere_density_kg_m3",
                                      "terminal_velocity_m_s", "Re_prime_printed", "Cd_printed"});
  std::map<int, int> seen;  // row_id -> line
  for (const auto& row : t.rows()) {
    SettlingSphere s;
    s.row_id = positive_id(t, row, "row_id");
    if (auto it = seen.find(s.row_id); it != seen.end())
      t.fail(row, "row_id", fmt::format("duplicate row_id {} (line {})", s.row_id, it->second));
    seen[s.row_id] = row.line;
    s.line = row.line;
    s.suspension = positive_id(t, row, "suspension");
    const auto& su = find_suspension(t, row, s.suspension, data.suspensions);
    s.sphere = {t.number(row, "diameter_m", Range::positive), t.number(row, "sphere_density_kg_m3", Range::positive),
                su.rho_f, su.tau_y, su.eta_B};
    s.v = t.number(row, "terminal_velocity_m_s", Range::positive);
    s.re_printed = t.number(row, "Re_prime_printed", Range::positive);
    s.cd_printed = t.number(row, "Cd_printed", Range::positive);
    if (s.sphere.rho_p <= s.sphere.rho_f)
      t.fail(row, "sphere_density_kg_m3",
             fmt::format("sphere density {} is not above its suspension's {} kg/m3: it cannot settle",
                         s.sphere.rho_p, s.sphere.rho_f));
    s.re = pastemix::drag::bingham_reynolds(s.sphere.rho_f, s.v, s.sphere.tau_y, s.sphere.eta_B, s.sphere.d);
    s.cd = pastemix::drag::settling_drag_coefficient(s.sphere, s.v, units::g);
    if (!(s.cd > 0.0))
      t.fail(row, "diameter_m", "the yield term exceeds the net weight (Cd <= 0 from eq. 4.17): it could not settle");
    const double re_err = std::abs(s.re / s.re_printed - 1.0), cd_err = std::abs(s.cd / s.cd_printed - 1.0);
    if (re_err > data.max_re_error) data.max_re_error = re_err, data.max_re_row = s.row_id;
    if (cd_err > data.max_cd_error) data.max_cd_error = cd_err, data.max_cd_row = s.row_id;
    data.spheres.push_back(s);
  }
  return data;
}

SettlingData read_settling_dataset(const std::filesystem::path& dir) {
  return read_settling_data(dir / "valentik_whitmore_1965_spheres.csv", dir / "valentik_whitmore_1965_suspensions.csv");
}

std::vector<ThesisModelRow> read_thesis_model(const std::filesystem::path& path,
                                              const std::vector<Suspension>& suspensions) {
  const auto t = read_exact(path, {"row_id", "suspension", "diameter_m", "radius_m", "sphere_density_kg_m3",
                                   "terminal_velocity_measured_m_s", "terminal_velocity_model_m_s",
                                   "clay_density_kg_m3", "clay_plastic_viscosity_Pa_s", "clay_yield_stress_Pa",
                                   "table_4_3_row_id", "correction"});
  std::vector<ThesisModelRow> out;
  for (const auto& row : t.rows()) {
    ThesisModelRow r;
    r.row_id = positive_id(t, row, "row_id");
    r.line = row.line;
    r.suspension = positive_id(t, row, "suspension");
    const auto& su = find_suspension(t, row, r.suspension, suspensions);
    // The printed clay properties must be those of the suspension (they are, on every row of A.1).
    auto same = [&](std::string_view col, double expected) {
      const double got = t.number(row, col, Range::non_negative);
      if (std::abs(got - expected) > 1e-9 * std::max(1.0, std::abs(expected)))
        t.fail(row, col, fmt::format("{} differs from suspension {}'s {} in the suspensions file", got, su.id, expected));
    };
    same("clay_density_kg_m3", su.rho_f);
    same("clay_plastic_viscosity_Pa_s", su.eta_B);
    same("clay_yield_stress_Pa", su.tau_y);
    r.sphere = {t.number(row, "diameter_m", Range::positive), t.number(row, "sphere_density_kg_m3", Range::positive),
                su.rho_f, su.tau_y, su.eta_B};
    const double radius = t.number(row, "radius_m", Range::positive);
    if (std::abs(2.0 * radius / r.sphere.d - 1.0) > 1e-6) t.fail(row, "radius_m", "radius is not half the diameter");
    r.v_measured = t.optional_number(row, "terminal_velocity_measured_m_s", Range::positive);
    r.v_model = t.optional_number(row, "terminal_velocity_model_m_s", Range::positive);
    if (t.text(row, "table_4_3_row_id").empty()) {
      r.spheres_row_id = std::nullopt;
    } else {
      r.spheres_row_id = positive_id(t, row, "table_4_3_row_id");
    }
    out.push_back(r);
  }
  return out;
}

}  // namespace pastemix::lab::drag
