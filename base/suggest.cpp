// SPDX-License-Identifier: MIT
#include "base/suggest.h"

#include <algorithm>

#include <fmt/format.h>

namespace pastemix {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment over three rows: the names compared are short (keys, column names).
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    prev2 = prev;
    prev = cur;
  }
  return prev[m];
}

std::string did_you_mean(std::string_view word, const std::vector<std::string>& known) {
  if (word.size() > 200) return {};  // not a typo of a name; and keeps the cost bounded
  std::string best;
  std::size_t best_d = 3;
  for (const auto& k : known) {
    if (k == word || k.size() > 200) continue;
    const std::size_t d = edit_distance(word, k);
    if (d < best_d && 2 * d < std::max(word.size(), k.size())) {
      best_d = d;
      best = k;
    }
  }
  return best.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", best);
}

std::string shown(std::string_view cell) {
  constexpr std::size_t max_chars = 60;
  if (cell.size() <= max_chars) return std::string(cell);
  return fmt::format("{}... ({} characters)", cell.substr(0, max_chars), cell.size());
}

}  // namespace pastemix
