// SPDX-License-Identifier: MIT
#include "base/store_rheology.h"

#include <cmath>

#include <fmt/format.h>

#include "base/error.h"
#include "base/params.h"

namespace pastemix {

StoreRheology read_store_rheology(const std::string& file, double solids_fraction, const std::string& at,
                                  StoreKeys keys) {
  const Params root = Params::parse_file(file);
  const auto pr = root.optional_table("paste_rheology");
  if (!pr)
    throw InputError(file, 0, "paste_rheology",
                     "missing: this store has no paste-rheology model; rerun `pastemix lab reduce datasets/thesis "
                     "--out out/lab`");
  std::string known;
  for (const std::string& key : pr->keys()) {
    if (key.rfind("cw_", 0) != 0) continue;
    const Params t = pr->table(key);
    const double cw = t.table("solids_fraction").number("value", Range::fraction);
    known += fmt::format("{}{:g}", known.empty() ? "" : ", ", cw);
    if (std::abs(cw - solids_fraction) > 1e-9) continue;
    StoreRheology s;
    s.key = "paste_rheology." + key;
    const Params band = at == "value" ? t : t.table(at);  // minus_sd / plus_sd: the protocol's band
    s.yield_stress = band.table("yield_stress").number("value", Range::non_negative);
    s.plastic_viscosity = band.table("plastic_viscosity").number("value", Range::positive);
    s.density = t.table("density").number("value", Range::positive);
    if (keys == StoreKeys::values_curve_provenance) {
      s.provenance = t.table("yield_stress").string("method");
      s.curve = pr->table("model").table("curve").string("text");
    }
    return s;  // not finish()ed: the store holds every lab parameter
  }
  throw InputError(file, 0, "paste_rheology",
                   fmt::format("no entry for solids content {:g} (the store has {}): the store's solids contents are "
                               "those of the mixing programme",
                               solids_fraction, known.empty() ? "none" : known));
}

}  // namespace pastemix
