// SPDX-License-Identifier: MIT
// Checks that the result files given to `pastemix score` are distinct realizations of one scene, and of the
// lab case they are scored against.
//
// An ensemble's mean and spread assume independent seeded runs of the same scene: a file given twice (or
// two files of the same seed) would count one realization as two, and files of different scenes (different
// scene hashes) are not an ensemble. A result scored against the wrong case (case 3 with --lab 5) is caught
// by the case's paste (solids fraction, from the mixing programme) and rock sizes (its PSD range).
#pragma once

#include <vector>

#include "analysis/maps/result_file.h"
#include "analysis/score/lab_case.h"

namespace pastemix::analysis {

// Paste solids differ between cases by 2.5 points (70 / 72.5 / 75 %): 1 point tells them apart and allows
// for a rounded value in a scene.
inline constexpr double kSolidsTolerance = 0.01;  // fraction
// A PSD cut or a scaling study moves sizes a little; a median diameter outside the case's sieve range by
// more than this relative margin is another case's rock.
inline constexpr double kDiameterMargin = 0.05;

// Throws InputError (naming the file, the field and both values) at the first inconsistency.
void check_realizations(const LabCase& lab, const std::vector<ResultSnapshot>& results);

}  // namespace pastemix::analysis
