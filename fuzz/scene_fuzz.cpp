// SPDX-License-Identifier: MIT
// libFuzzer target: the scene loader (model/scene.h) with --set paths (model/scene_doc.h).
//
// Input: a scene's TOML text, optionally followed by a line "%%" and `key.path=value` lines, applied in
// order as `pastemix run --set` would.
#include <string>
#include <vector>

#include "fuzz/fuzz_common.h"
#include "model/scene.h"
#include "model/scene_doc.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pastemix;
  std::string text(fuzz::as_text(data, size));
  std::vector<std::string> sets;
  if (const auto cut = text.find("\n%%\n"); cut != std::string::npos) {
    std::string rest = text.substr(cut + 4);
    text.resize(cut + 1);
    for (std::size_t at = 0; at < rest.size();) {
      const auto nl = rest.find('\n', at);
      const std::string line = rest.substr(at, nl == std::string::npos ? std::string::npos : nl - at);
      if (!line.empty()) sets.push_back(line);
      at = nl == std::string::npos ? rest.size() : nl + 1;
    }
  }
  fuzz::guarded([&] {
    model::SceneDoc doc = model::SceneDoc::parse(text, PASTEMIX_SOURCE_DIR "/datasets/scenes/fuzz.toml");
    for (const auto& s : sets) doc.apply(s);
    const model::Scene scene = doc.load();
    (void)model::make_world(scene);
  });
  return 0;
}
