#include "observer/modelfest.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <stdexcept>

namespace countershade::observer {
namespace {

constexpr double kPi = std::numbers::pi;
using Pattern = std::function<double(double x, double y)>;  // degrees from the centre

double envelope(double x, double y, double sx, double sy) {
  return std::exp(-x * x / (2 * sx * sx) - y * y / (2 * sy * sy));
}

// A carrier of f c/deg whose wave vector is θ degrees from vertical: θ = 0 is a horizontal
// grating (ModelFest's default), 90 a vertical one.
double carrier(double x, double y, double f, double theta_degrees, double phase = 0) {
  const double t = theta_degrees * kPi / 180;
  return std::cos(2 * kPi * f * (x * std::sin(t) + y * std::cos(t)) + phase);
}

Pattern gabor(double f, double sx, double sy, double theta = 0) {
  return [=](double x, double y) { return carrier(x, y, f, theta) * envelope(x, y, sx, sy); };
}

Pattern sum(Pattern a, Pattern b) {
  return [=](double x, double y) { return a(x, y) + b(x, y); };
}

// Five Gabors along their bars (x), 5s apart, with these carrier phases.
Pattern gabor_row(double f, double s, const double (&phases)[5]) {
  return [=](double x, double y) {
    double v = 0;
    for (int k = 0; k < 5; ++k) {
      const double cx = (k - 2) * 5 * s;
      v += std::cos(2 * kPi * f * y + phases[k]) * envelope(x - cx, y, s, s);
    }
    return v;
  };
}

// The pattern sampled at pixel centres, scaled to a peak |contrast| of 1.
ContrastImage sampled(const Pattern& pattern, double ppd, int size) {
  ContrastImage image(size, size);
  double peak = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double v = pattern((i - size / 2) / ppd, (j - size / 2) / ppd);
      image.at(i, j) = v;
      peak = std::max(peak, std::abs(v));
    }
  for (double& v : image.values) v /= peak;
  return image;
}

struct Definition {
  int number;
  const char* family;
  Pattern pattern;
};

std::vector<Definition> definitions(double ppd) {
  std::vector<Definition> d;
  const double gabor_f[] = {1.12, 2, 2.83, 4, 5.66, 8, 11.3, 16, 22.6, 30};
  for (int i = 0; i < 10; ++i) d.push_back({1 + i, "Gabor s=0.5°", gabor(gabor_f[i], 0.5, 0.5)});
  const double fixed_f[] = {2, 4, 8, 16}, fixed_s[] = {0.28, 0.14, 0.07, 0.035};
  for (int i = 0; i < 4; ++i)
    d.push_back({11 + i, "fixed-bandwidth Gabor", gabor(fixed_f[i], fixed_s[i], fixed_s[i])});
  const double long_f[] = {4, 8, 16}, long_sy[] = {0.28, 0.14, 0.07};
  for (int i = 0; i < 3; ++i)
    d.push_back({15 + i, "elongated Gabor", gabor(long_f[i], 0.5, long_sy[i])});
  const double baguette[4][2] = {{0.14, 0.28}, {0.14, 0.5}, {0.28, 0.14}, {0.5, 0.14}};  // sy, sx
  for (int i = 0; i < 4; ++i)
    d.push_back({18 + i, "baguette", gabor(4, baguette[i][1], baguette[i][0])});
  const double pairs[4][2] = {{2, 2.83}, {2, 4}, {4, 5.66}, {4, 8}};
  for (int i = 0; i < 4; ++i)
    d.push_back({22 + i, "compound Gabors",
                 sum(gabor(pairs[i][0], 0.5, 0.5), gabor(pairs[i][1], 0.5, 0.5))});
  for (auto [number, arcmin] : {std::pair{27, 8.43}, std::pair{29, 1.05}}) {
    const double s = arcmin / 60;
    d.push_back(
        {number, "Gaussian blob", [=](double x, double y) { return envelope(x, y, s, s); }});
  }
  const double half_pixel = 0.5 / ppd;
  d.push_back({31, "line", [=](double x, double y) {
                 return std::abs(y) < half_pixel ? envelope(x, 0, 0.5, 0.5) : 0.0;
               }});
  const double same[5] = {0, 0, 0, 0, 0},
               alternating[5] = {kPi / 2, -kPi / 2, kPi / 2, -kPi / 2, kPi / 2};
  d.push_back({33, "Gabor row", gabor_row(8, 0.07, same)});
  d.push_back({34, "Gabor row", gabor_row(8, 0.07, alternating)});
  d.push_back({36, "orientation and plaid", gabor(4, 0.14, 0.14, 45)});
  d.push_back({37, "orientation and plaid", gabor(4, 0.14, 0.14, 90)});
  d.push_back(
      {38, "orientation and plaid", sum(gabor(4, 0.14, 0.14, 0), gabor(4, 0.14, 0.14, 90))});
  d.push_back(
      {39, "orientation and plaid", sum(gabor(4, 0.14, 0.14, 45), gabor(4, 0.14, 0.14, 90))});
  d.push_back({41, "Bessel", [](double x, double y) {
                 const double r = std::hypot(x, y);
                 return std::cyl_bessel_j(0.0, 2 * kPi * 4 * r) * envelope(x, y, 0.5, 0.5);
               }});
  // Checks at 45° whose fundamentals, on the axes, are 4 c/deg: the sign of the sum of a
  // horizontal and a vertical 4 c/deg grating.
  d.push_back({42, "checkerboard", [](double x, double y) {
                 const double v = std::cos(2 * kPi * 4 * x) + std::cos(2 * kPi * 4 * y);
                 return (v > 0 ? 1.0 : v < 0 ? -1.0 : 0.0) * envelope(x, y, 0.5, 0.5);
               }});
  return d;
}

}  // namespace

std::vector<ModelfestStimulus> modelfest_stimuli(double ppd, int size) {
  std::vector<ModelfestStimulus> out;
  for (const Definition& d : definitions(ppd))
    out.push_back({d.number, d.family, sampled(d.pattern, ppd, size)});
  return out;
}

namespace {

// Per stimulus, log10 of its pooled filtered response at unit peak contrast, for one β.
struct Responses {
  std::vector<ContrastImage> filtered;
  double ppd;
  std::vector<double> log10_at(double beta) const {
    std::vector<double> out;
    for (const auto& f : filtered) out.push_back(std::log10(minkowski_pool(f, beta, ppd)));
    return out;
  }
};

// The gain that minimises the squared error in dB for these responses, and the fit's rows.
ModelfestFit fit_gain(const std::vector<ModelfestStimulus>& stimuli,
                      const std::vector<double>& observed, const std::vector<double>& log10_r,
                      DetectionModel model) {
  // A threshold c gives 1 JND: gain·c·R = 1, so 20·log10 c = −20·log10(gain) − 20·log10 R.
  double mean = 0;
  for (size_t i = 0; i < observed.size(); ++i) mean += observed[i] + 20 * log10_r[i];
  mean /= double(observed.size());
  model.gain = std::pow(10.0, -mean / 20);
  ModelfestFit fit;
  fit.model = model;
  double squares = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    const double predicted = -20 * std::log10(model.gain) - 20 * log10_r[i];
    fit.rows.push_back({stimuli[i].number, stimuli[i].family, observed[i], predicted});
    squares += (predicted - observed[i]) * (predicted - observed[i]);
  }
  fit.rms_db = std::sqrt(squares / double(observed.size()));
  return fit;
}

// The β in [1, 8] where `error` is least: a scan in steps of 0.25, then golden-section search
// around the best step (the error is smooth and, near its minimum, unimodal in β).
double minimise_over_beta(const std::function<double(double)>& error) {
  double best = 1, best_error = error(1);
  for (double beta = 1.25; beta <= 8; beta += 0.25)
    if (const double e = error(beta); e < best_error) best = beta, best_error = e;
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double lo = std::max(1.0, best - 0.25), hi = std::min(8.0, best + 0.25);
  double a = hi - ratio * (hi - lo), b = lo + ratio * (hi - lo);
  double ea = error(a), eb = error(b);
  for (int k = 0; k < 25; ++k) {
    if (ea < eb) {
      hi = b, b = a, eb = ea, a = hi - ratio * (hi - lo), ea = error(a);
    } else {
      lo = a, a = b, ea = eb, b = lo + ratio * (hi - lo), eb = error(b);
    }
  }
  return (lo + hi) / 2;
}

}  // namespace

ModelfestFit fit_modelfest(const std::vector<ModelfestStimulus>& stimuli,
                           const std::vector<ModelfestThreshold>& thresholds, double ppd,
                           bool oblique) {
  std::map<int, double> by_number;
  for (const auto& t : thresholds) by_number[t.number] = t.threshold_db;
  Responses responses{{}, ppd};
  std::vector<double> observed;
  for (const auto& s : stimuli) {
    if (!by_number.count(s.number))
      throw std::invalid_argument("no threshold for ModelFest stimulus " +
                                  std::to_string(s.number));
    observed.push_back(by_number[s.number]);
    responses.filtered.push_back(csf_filtered(s.image, ppd, oblique));
  }
  const auto fit_at = [&](double beta) {
    return fit_gain(stimuli, observed, responses.log10_at(beta), {1, beta, oblique});
  };
  return fit_at(minimise_over_beta([&](double beta) { return fit_at(beta).rms_db; }));
}

std::vector<std::pair<std::string, double>> rms_by_family(const ModelfestFit& fit) {
  std::vector<std::pair<std::string, double>> out;
  std::map<std::string, std::pair<double, int>> sums;
  for (const auto& row : fit.rows) {
    auto& [squares, count] = sums[row.family];
    if (count == 0) out.push_back({row.family, 0});
    squares += (row.predicted_db - row.observed_db) * (row.predicted_db - row.observed_db);
    ++count;
  }
  for (auto& [family, rms] : out) rms = std::sqrt(sums[family].first / sums[family].second);
  return out;
}

}  // namespace countershade::observer
