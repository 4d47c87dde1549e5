// SPDX-License-Identifier: MIT
// Scoring drag curves by the terminal velocity they predict, in sample and leave-one-suspension-out.
//
// The LOSO loop refits from scratch on the five training suspensions with the same options each time and
// predicts the sixth; nothing about the held-out suspension reaches its fit. The chosen candidate is the one
// with the lowest LOSO mean |v_pred/v - 1| among the fitted candidates (a rule fixed before looking), so its
// LOSO score carries the small optimism of choosing among a handful of candidates.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "lab/drag/drag_fit.h"
#include "lab/drag/settling.h"
#include "lab/drag/terminal_velocity.h"

namespace pastemix::lab::drag {

struct Prediction {
  int row_id = 0;  // Table 4.3 row (A.1 row for the thesis model)
  int suspension = 0;
  double v_measured = 0.0;
  double v_predicted = 0.0;  // 0 if suspended; the trap bracket's midpoint if no consistent solution
  SettlingOutcome outcome = SettlingOutcome::settling;
  double rel_error() const { return v_predicted / v_measured - 1.0; }
};

struct Score {
  std::string label;
  int n = 0;
  double mean_abs = 0.0, median_abs = 0.0, max_abs = 0.0;  // of |v_pred/v - 1|
  int above_20 = 0;                                        // |rel. error| > 20 %
  int trapped = 0;                                         // no consistent solution / multiple roots
  int suspended = 0;
};

Score score(std::string label, std::span<const Prediction> predictions);

// Predicts every sphere with the full (scanning) solver.
std::vector<Prediction> predict(const DragCurve& curve, std::span<const SettlingSphere> spheres, double g);

struct Candidate {
  pastemix::drag::CurveId family;
  FitOptions options;
  CurveFit in_sample;
  std::vector<int> loso_suspensions;  // held-out suspension of each LOSO fit
  std::vector<CurveFit> loso_fits;
  std::vector<Prediction> in_sample_predictions, loso_predictions;  // in spheres order
  Score in_sample_score, loso_score;
  std::string name() const;  // "power_blend/velocity"
};

Candidate evaluate_candidate(pastemix::drag::CurveId family, const FitOptions& options,
                             std::span<const SettlingSphere> spheres, double g);

struct DragFitResult {
  std::filesystem::path dataset_dir;
  SettlingData data;
  std::string thesis_model_file;
  std::vector<ThesisModelRow> thesis_rows;
  std::vector<Prediction> published;  // (a)
  Score published_score;
  std::vector<Candidate> candidates;  // (b), (c) for each
  int chosen = 0;
  std::vector<Prediction> thesis_model;  // (d): the 90 A.1 pairs with both values
  Score thesis_score;
  // Like for like with (d): the chosen curve's LOSO and the published curve on the same (Table 4.3) spheres.
  Score loso_on_thesis_spheres, published_on_thesis_spheres;
  // The published curve through our force balance against the thesis f-EDEM output (v_measured := A.1 model
  // speed): how well the solver reproduces the thesis's own model.
  Score published_vs_thesis_model;
  const Candidate& best() const { return candidates[chosen]; }
};

// Reads the three files in `dir`, scores the published curve and the thesis model, fits and scores every
// candidate (fitted family x target), and picks one. Throws InputError for bad input.
// `with_robust` adds the same candidates fitted with a Cauchy loss (scale 0.1 in ln units).
DragFitResult run_drag_fit(const std::filesystem::path& dir, double g, bool with_robust = false);

// The candidate set drag-fit evaluates: fitted families x targets (x losses if with_robust).
std::vector<std::pair<pastemix::drag::CurveId, FitOptions>> default_candidates(bool with_robust = false);

}  // namespace pastemix::lab::drag
