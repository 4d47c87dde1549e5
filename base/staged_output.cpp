// SPDX-License-Identifier: MIT
#include "base/staged_output.h"

#include <unistd.h>

#include <fstream>

#include <fmt/format.h>

namespace pastemix {

StagedOutput::~StagedOutput() {
  if (committed_) return;
  std::error_code ec;
  for (const auto& t : temps_) std::filesystem::remove(t, ec);
}

std::filesystem::path StagedOutput::path(const std::filesystem::path& final_path) {
  if (final_path.has_parent_path()) std::filesystem::create_directories(final_path.parent_path());
  auto temp = final_path;
  temp += fmt::format(".partial-{}", static_cast<long>(::getpid()));
  finals_.push_back(final_path);
  temps_.push_back(temp);
  return temp;
}

void StagedOutput::write_text(const std::filesystem::path& final_path, const std::string& text) {
  auto temp = path(final_path);
  std::ofstream out(temp, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", temp.string()));
}

void StagedOutput::commit() {
  for (std::size_t k = 0; k < finals_.size(); ++k) std::filesystem::rename(temps_[k], finals_[k]);
  committed_ = true;
}

}  // namespace pastemix
