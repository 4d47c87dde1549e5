// SPDX-License-Identifier: MIT
// "Did you mean ...?" for a misspelt key or column: the nearest known name by edit distance.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace pastemix {

// Levenshtein distance (insert, delete, substitute, and swapping two neighbours each cost 1).
std::size_t edit_distance(std::string_view a, std::string_view b);
// " (did you mean 'x'?)" for the known name nearest to `word`, if it is close enough to be a typo (at most
// 2 edits and under half the word); "" otherwise.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& known);
// `cell` for an error message: long ones are cut, so a 10 MB cell is not echoed whole.
std::string shown(std::string_view cell);

}  // namespace pastemix
