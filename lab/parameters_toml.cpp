// SPDX-License-Identifier: MIT
#include "lab/parameters_toml.h"

#include <cmath>
#include <ctime>

#include <fmt/format.h>

#include "lab/ingest/ingest.h"
#include "pastemix_git.h"  // generated: PASTEMIX_GIT (cmake/git_version.cmake)

namespace pastemix::lab {

std::string software_version() {
#ifdef PASTEMIX_VERSION
  return std::string("pastemix ") + PASTEMIX_VERSION + " (" + PASTEMIX_GIT + ")";
#else
  return "pastemix (unknown version)";
#endif
}

std::string utc_now() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

namespace {

std::string toml_string(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

// Text for a "# ..." comment: every line of it starts with '#', whatever the message holds (a helper's
// multi-line output once made the file invalid TOML).
std::string commented(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '\r') continue;
    out += c;
    if (c == '\n') out += "#     ";
  }
  return out;
}

// Round-trip precision, trimmed: TOML readers get the exact double, people get short numbers where exact.
std::string number(double v) {
  if (std::isnan(v)) return "nan";
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eE") == std::string::npos && s.find("inf") == std::string::npos) s += ".0";
  return s;
}

std::string array(const std::vector<double>& v) {
  std::vector<std::string> parts;
  for (double x : v) parts.push_back(number(x));
  return fmt::format("[{}]", fmt::join(parts, ", "));
}

void psd_table(std::string& out, const std::string& key, const Psd& psd, const std::string& source,
               Provenance provenance, const std::string& comment) {
  std::vector<double> lo, hi, f;
  for (const auto& iv : psd.intervals) {
    lo.push_back(iv.d_min);
    hi.push_back(iv.d_max);
    f.push_back(iv.mass_fraction);
  }
  out += fmt::format("\n# {}\n[{}]\n", commented(comment), key);
  out += fmt::format("d_min_m = {}\nd_max_m = {}\nmass_fraction = {}\n", array(lo), array(hi), array(f));
  out += fmt::format("provenance = {}\nsource = {}\n", toml_string(to_string(provenance)), toml_string(source));
}

}  // namespace

std::string parameters_toml(const ReduceResult& r, const RunInfo& info) {
  std::string out;
  out += "# Parameters reduced from laboratory data by `pastemix lab reduce`.\n";
  out += fmt::format("# software: {}\n# command: {}\n# created: {}\n", info.software, info.command, info.created);
  out += fmt::format("# dataset: {} ({})\n# manifest: {}\n", r.dataset_dir, r.dataset_name, r.manifest);
  out += "# Units are SI; sd is the sample standard deviation of the trials (absent when unknown); source is\n"
         "# relative to the dataset folder. Warnings about the inputs are listed at the end.\n\n";
  out += "[reduce]\n";
  out += fmt::format("software = {}\ndataset = {}\nmanifest = {}\n", toml_string(info.software), toml_string(r.dataset_dir),
                     toml_string(r.manifest));
  std::vector<std::string> steps, inputs;
  for (const auto& s : r.steps_run) steps.push_back(toml_string(s));
  for (const auto& s : r.inputs) inputs.push_back(toml_string(s));
  out += fmt::format("steps = [{}]\ninputs = [{}]\n", fmt::join(steps, ", "), fmt::join(inputs, ", "));
  for (const auto& p : r.parameters) {
    std::string words = std::isnan(p.value) ? p.text : format_value(p.value);
    if (std::isfinite(p.sd)) words += " +- " + format_value(p.sd);
    words += " " + p.unit;
    if (p.n > 0) words += fmt::format(" (n = {})", p.n);
    out += fmt::format("\n# {}: {}\n[{}]\n", p.key, commented(words), p.key);
    if (!std::isnan(p.value)) out += fmt::format("value = {}\n", number(p.value));
    if (!p.text.empty()) out += fmt::format("text = {}\n", toml_string(p.text));
    if (std::isfinite(p.sd)) out += fmt::format("sd = {}\n", number(p.sd));
    if (p.n > 0) out += fmt::format("n = {}\n", p.n);
    out += fmt::format("unit = {}\nprovenance = {}\nmethod = {}\nsource = {}\n", toml_string(p.unit),
                       toml_string(to_string(p.provenance)), toml_string(p.method), toml_string(p.source));
    if (!p.trials.empty()) out += fmt::format("trials = {}\n", array(p.trials));
    if (!p.note.empty()) out += fmt::format("note = {}\n", toml_string(p.note));
  }
  for (const auto& c : r.mixing_cases)
    psd_table(out, fmt::format("mixing.case_{}.psd", c.case_id), c.psd, r.mixing_source,
              Provenance::measured,
              fmt::format("case {}: sieve range {} to {} mm; the thesis gives no sieve masses, so one interval", c.case_id,
                          c.psd.d_min() * 1e3, c.psd.d_max() * 1e3));
  for (const auto& s : r.sieves)
    psd_table(out, fmt::format("psd.{}", s.name), s.result.psd, s.source, s.provenance,
              s.note.empty() ? fmt::format("sieve analysis {}", s.name) : s.note);
  if (!r.warnings.empty()) {
    out += "\n# Warnings about the inputs:\n";
    for (const auto& w : r.warnings) out += fmt::format("#   {}: {}\n", commented(w.where), commented(w.message));
  }
  return out;
}

}  // namespace pastemix::lab
