#pragma once
// The adjustment study's simulated observer (--observer simulated:SEED): its key events go
// through the same session loop as a person's.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "adjust/procedure.h"
#include "runtime/key_script.h"
#include "runtime/study.h"

namespace countershade::adjust {

// A model observer: for every condition it has latent thresholds for the three questions, drawn
// from the seed, and answers with the first grid index at or above them. It is deterministic
// given the seed, so tests know every answer in advance.
//
// Its thresholds lie at fixed shares of the grid's top, unless `predicted` gives, per condition,
// the image-computable observer's λ at 1, 2 and 4 JND (--observer model:SEED,
// observer/model_observer.h; +∞ where the grid ends first): λ_Low then lies near 1 JND, λ_Best
// near 2 and λ_High near 4 (Ritschel et al. 2008, Fig. 12), each scaled by the observer's own
// sensitivity and by answer noise.
class SimulatedObserver {
 public:
  using PredictedLevels = std::vector<std::array<double, 3>>;
  SimulatedObserver(uint64_t seed, const runtime::Study& study, double step_interval_s = 0.02,
                    PredictedLevels predicted = {});

  // The latent λ of a question for a condition and repetition, and the grid index answered.
  double latent_lambda(int condition, int repetition, Question question) const;
  int answer_index(int condition, int repetition, Question question) const;

  // The observer's next key events, given what is on screen now.
  std::vector<runtime::InputEvent> act(const Procedure& procedure, double time_s);

 private:
  uint64_t seed_;
  const runtime::Study& study_;
  PredictedLevels predicted_;
  double interval_s_;
  double next_action_s_ = 0;
};

// Parses "simulated:SEED"; throws InputError for anything else.
uint64_t parse_observer_spec(const std::string& spec);

}  // namespace countershade::adjust
