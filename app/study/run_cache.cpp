// SPDX-License-Identifier: MIT
#include "app/study/run_cache.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "base/error.h"
#include "base/hash.h"
#include "base/params.h"
#include "base/staged_output.h"

namespace pastemix::app::study {
namespace {

// A TOML basic string: quotes, backslashes and control characters escaped (failure messages are free text).
std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7f) {
      out += fmt::format("\\u{:04x}", c);
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

}  // namespace

std::string run_key(const model::SceneDoc& doc, const std::string& qoi) {
  return text_hash("qoi = " + qoi + "\n" + doc.text());
}

std::optional<RunRecord> RunCache::find(const std::string& key) const {
  if (!enabled()) return std::nullopt;
  const std::filesystem::path p = record_path(key);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(p, ec)) return std::nullopt;
  try {
    const Params t = Params::parse_file(p);
    if (t.string("key") != key) throw InputError(p.string(), t.line_of("key"), "key", "is not the file's name");
    RunRecord r;
    const std::string status = t.choice("status", {"done", "failed"});
    r.failed = status == "failed";
    r.engine = t.string_or("engine", "");
    if (r.failed) {
      r.failure = t.string("failure");
    } else {
      r.qoi = t.numbers("qoi");
      r.wall_s = t.number("wall_s", Range::non_negative);
      r.work = t.number("work", Range::non_negative);
      r.particles = static_cast<std::size_t>(t.integer("particles"));
    }
    for (const char* k : {"scene", "run"}) t.ignore(k);
    t.finish();
    return r;
  } catch (const InputError& e) {
    fmt::print(stderr, "warning: ignoring the study record {} ({}); the run is done again\n", p.string(), e.what());
    return std::nullopt;
  }
}

void RunCache::store(const std::string& key, const RunRecord& r, const std::string& scene,
                     const std::string& what) const {
  if (!enabled()) return;
  std::string text = fmt::format(
      "# A finished run of a pastemix study (app/study/run_cache.h). A rerun of the study reads it back\n"
      "# instead of running again; delete it to rerun this one point.\n"
      "key = \"{}\"\nscene = {}\nrun = {}\nengine = {}\nstatus = \"{}\"\n",
      key, toml_string(scene), toml_string(what), toml_string(r.engine), r.failed ? "failed" : "done");
  if (r.failed)
    text += "failure = " + toml_string(r.failure) + "\n";
  else
    text += fmt::format("qoi = [{:.17g}]\nwall_s = {:.6g}\nwork = {:.17g}\nparticles = {}\n", fmt::join(r.qoi, ", "),
                        r.wall_s, r.work, r.particles);
  StagedOutput out;
  out.write_text(record_path(key), text);
  out.commit();
}

}  // namespace pastemix::app::study
