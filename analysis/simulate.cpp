#include "analysis/simulate.h"

#include <algorithm>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

#include "core/atomic_file.h"
#include "core/random.h"

namespace countershade::analysis {
namespace {

double normal(SampleStream& random) {
  double u = std::clamp(random.next(), 1e-12, 1.0 - 1e-12);
  return -std::numbers::sqrt2 * boost::math::erfc_inv(2.0 * u);
}

// λ_i on the decimal grid, as a stimulus set writes it.
double grid_value(const SimulationDesign& d, int index) {
  return std::round((d.lambda_min + index * d.lambda_step) * 1e9) / 1e9;
}

// The index of the first grid value at or above t, at most the top of the grid.
int grid_index(const SimulationDesign& d, double t) {
  const int top = int(std::floor((d.lambda_max - d.lambda_min) / d.lambda_step + 1e-9));
  const double steps = std::ceil((t - d.lambda_min) / d.lambda_step - 1e-9);
  return int(std::clamp(steps, 0.0, double(top)));
}

}  // namespace

std::vector<Response> simulate_responses(const SimulationDesign& d) {
  std::vector<Response> out;
  for (int s = 0; s < d.subjects; ++s) {
    char id[32];
    std::snprintf(id, sizeof id, "S%03d", s + 1);
    SampleStream subject_random(d.seed, 11, uint64_t(s), 0);
    const bool weak = subject_random.next() < d.weak_fraction;
    const double low_offset = d.low_subject_sd * normal(subject_random);
    for (size_t sc = 0; sc < d.scenes.size(); ++sc)
      for (size_t g = 0; g < d.sigmas.size(); ++g)
        for (int rep = 0; rep < d.repetitions; ++rep)
          for (int q = 0; q < 3; ++q) {
            SampleStream random(
                d.seed, 12,
                (uint64_t(s) * 1000 + sc * 100 + g * 10 + uint64_t(q)) * 64 + uint64_t(rep), 0);
            double log_low = std::log(d.low) + low_offset;
            double log_lambda = log_low;
            if (q == int(Question::best)) log_lambda += std::log(d.best_jnd[weak ? 0 : 1]);
            if (q == int(Question::high))
              log_lambda += std::log(d.high_jnd) + d.high_sigma_slope * double(g);
            log_lambda += d.answer_sd * normal(random);
            Response r;
            r.subject = id;
            r.scene = d.scenes[sc];
            r.sigma = d.sigmas[g];
            r.question = Question(q);
            r.lambda_index = grid_index(d, std::exp(log_lambda));
            r.lambda = grid_value(d, r.lambda_index);
            r.lambda_step = d.lambda_step;
            r.lambda_max = grid_value(d, grid_index(d, d.lambda_max));
            r.method = d.method;
            r.source = "simulated";
            out.push_back(r);
          }
  }
  return out;
}

void write_responses_csv(const std::vector<Response>& responses, const std::string& path,
                         double lambda_step) {
  std::ostringstream csv;
  csv.precision(12);
  csv << "subject,scene,sigma,question,lambda,lambda_step,lambda_index,lambda_max,method\n";
  for (const auto& r : responses)
    csv << csv_field(r.subject) << "," << csv_field(r.scene) << "," << r.sigma << ","
        << kQuestionNames[int(r.question)] << "," << r.lambda << "," << lambda_step << ","
        << r.lambda_index << "," << r.lambda_max << "," << csv_field(r.method) << "\n";
  write_text_atomically(path, csv.str());
}

}  // namespace countershade::analysis
