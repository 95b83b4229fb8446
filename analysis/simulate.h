#pragma once
// Synthetic observers for tests and for planning a study's sample size: per-subject thresholds
// (log-normal around each condition's group threshold), a λ_Best preference drawn from one of
// two clusters, a σ effect on λ_High, and answers quantised to the stimulus grid (each answer is
// the first grid value at or above the observer's latent threshold, and the top of the grid when
// the threshold lies beyond it).

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/responses.h"

namespace countershade::analysis {

struct SimulationDesign {
  int subjects = 15;
  std::vector<std::string> scenes = {"chamfer", "dice", "feet", "keys"};
  std::vector<double> sigmas = {0.01, 0.02, 0.04};
  double lambda_min = 0, lambda_step = 0.05, lambda_max = 3.0;  // the grid λ_i = min + i·step ≤ max
  int repetitions = 1;
  double low = 0.3;                 // group threshold λ_Low
  double low_subject_sd = 0.25;     // between-subject SD of ln λ_Low
  double answer_sd = 0.15;          // within-subject SD of ln λ (every answer)
  double best_jnd[2] = {1.4, 1.9};  // λ_Best in JND of the two preference clusters
  double weak_fraction = 1.0 / 3;   // share of subjects in the weak-enhancement cluster
  double high_jnd = 4.0;            // λ_High in JND at the smallest σ
  double high_sigma_slope = -0.1;   // change of ln λ_High per σ step
  uint64_t seed = 1;
  std::string method = "simulated";  // the method column: one analysis block
};

// One response per subject × scene × σ × question × repetition, in a reproducible order.
std::vector<Response> simulate_responses(const SimulationDesign& design);

// Writes responses as the CSV of docs/data-formats (required columns plus lambda_step,
// lambda_index, lambda_max, repetition and method).
void write_responses_csv(const std::vector<Response>& responses, const std::string& path,
                         double lambda_step);

}  // namespace countershade::analysis
