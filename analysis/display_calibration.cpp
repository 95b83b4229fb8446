#include "analysis/display_calibration.h"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>

#include "analysis/bounded_least_squares.h"
#include "core/error.h"
#include "core/file_bytes.h"
#include "formats/responses.h"

namespace countershade::analysis {
namespace {

using Objective = std::function<double(double)>;

// The minimum of f over [lo, hi]: the best of a grid, then Brent's method between its neighbours
// (to about 1e-8 relative, the square root of double's precision). A minimum on a bound comes
// back exactly on it.
double minimize_1d(const Objective& f, double lo, double hi) {
  constexpr int kGrid = 32;
  int best = 0;
  double best_value = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kGrid; ++i) {
    const double v = f(lo + (hi - lo) * i / kGrid);
    if (v < best_value) best = i, best_value = v;
  }
  const double a = lo + (hi - lo) * std::max(0, best - 1) / kGrid,
               b = lo + (hi - lo) * std::min(kGrid, best + 1) / kGrid;
  std::uintmax_t iterations = 200;
  const auto [x, value] = boost::math::tools::brent_find_minima(
      f, a, b, std::numeric_limits<double>::digits, iterations);
  double out = x;
  for (double bound : {lo, hi})
    if (std::abs(out - bound) < 1e-7 * (hi - lo) && f(bound) <= value) out = bound;
  return out;
}

double rss_of(const std::vector<Reading>& r, const std::function<double(double)>& model) {
  double sum = 0;
  for (const Reading& p : r) {
    const double residual = model(p.level) - p.luminance;
    sum += residual * residual;
  }
  return sum;
}

// psyphy: for a given exponent the black level and gain are a linear least-squares problem.
struct LinearPart {
  double blev = 0, k = 0;
};
LinearPart black_and_gain(const std::vector<Reading>& r, double g) {
  double n = 0, su = 0, suu = 0, sl = 0, sul = 0;
  for (const Reading& p : r) {
    const double u = std::pow(p.level, g);
    n += 1, su += u, suu += u * u, sl += p.luminance, sul += u * p.luminance;
  }
  const double det = n * suu - su * su;
  return {(suu * sl - su * sul) / det, (n * sul - su * sl) / det};
}

GammaFit fit_psyphy(const std::vector<Reading>& r) {
  auto rss_at = [&](double g) {
    const LinearPart p = black_and_gain(r, g);
    return rss_of(r, [&](double x) { return p.blev + p.k * std::pow(x, g); });
  };
  const double g = minimize_1d(rss_at, 0.1, 10.0);
  const LinearPart p = black_and_gain(r, g);
  GammaFit fit{"psyphy", {{"Blev", p.blev}, {"k", p.k}, {"gamm", g}}, {}, rss_at(g)};
  // Standard errors as R's nls: sqrt(diag(s²·(JᵀJ)⁻¹)), s² = rss / (n − 3). JᵀJ is summed row by
  // row of J at fixed size: a dynamic-size product and inverse would instantiate Eigen's matrix
  // kernels, a third of this file's compile.
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  for (const Reading& reading : r) {
    const double u = std::pow(reading.level, g);
    const Eigen::Vector3d row(1, u, reading.level > 0 ? p.k * u * std::log(reading.level) : 0.0);
    normal += row * row.transpose();
  }
  const Eigen::Matrix3d covariance = normal.inverse() * (fit.rss / double(r.size() - 3));
  const char* names[] = {"Blev", "k", "gamm"};
  for (int c = 0; c < 3; ++c) fit.se[names[c]] = std::sqrt(covariance(c, c));
  return fit;
}

GammaFit fit_eq1(const std::vector<Reading>& r) {
  const double lo = r.front().luminance, hi = r.back().luminance;
  auto model = [&](double g) { return [=](double x) { return lo + (hi - lo) * std::pow(x, g); }; };
  const double g = minimize_1d([&](double g) { return rss_of(r, model(g)); }, 0.8, 5.0);
  return {"psychopy-eq1",
          {{"gamma", g}, {"a", lo}, {"b", std::pow(hi - lo, 1.0 / g)}},
          {},
          rss_of(r, model(g))};
}

GammaFit fit_eq2(const std::vector<Reading>& r) {
  const double lo = r.front().luminance, hi = r.back().luminance;
  auto model = [&](double g) {
    const double a = std::pow(lo, 1.0 / g), b = std::pow(hi, 1.0 / g) - a;
    return [=](double x) { return std::pow(a + b * x, g); };
  };
  const double g = minimize_1d([&](double g) { return rss_of(r, model(g)); }, 0.8, 5.0);
  const double a = std::pow(lo, 1.0 / g);
  return {"psychopy-eq2",
          {{"gamma", g}, {"a", a}, {"b", std::pow(hi, 1.0 / g) - a}},
          {},
          rss_of(r, model(g))};
}

// Pelli & Zhang's model, L = a + (b + k·x)^γ with b = (L(0) − a)^(1/γ): its residuals at
// p = {γ, a, k}.
struct PelliZhangResiduals {
  const std::vector<Reading>& readings;
  int count() const { return int(readings.size()); }
  template <typename T>
  void operator()(const T* p, T* residuals) const {
    using std::pow;
    const T b = pow(T(readings.front().luminance) - p[1], T(1.0) / p[0]);
    for (size_t i = 0; i < readings.size(); ++i)
      residuals[i] = p[1] + pow(b + p[2] * readings[i].level, p[0]) - T(readings[i].luminance);
  }
};

// The grid points over the whole box (γ and a linearly, k logarithmically) with the lowest
// residual sums, best first.
std::vector<ParameterVector<3>> best_grid_points(const PelliZhangResiduals& residuals,
                                                 const ParameterBox<3>& box, int count) {
  constexpr int kSteps = 8;
  const auto& [lo, hi] = box;
  std::vector<std::pair<double, ParameterVector<3>>> scored;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; j <= kSteps; ++j)
      for (int l = 0; l <= kSteps; ++l) {
        const ParameterVector<3> p(lo[0] + (hi[0] - lo[0]) * i / kSteps,
                                   lo[1] + (hi[1] - lo[1]) * j / kSteps,
                                   lo[2] * std::pow(hi[2] / lo[2], double(l) / kSteps));
        scored.push_back({sum_of_squares<3>(residuals, p), p});
      }
  std::partial_sort(scored.begin(), scored.begin() + count, scored.end(),
                    [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<ParameterVector<3>> out;
  for (int i = 0; i < count; ++i) out.push_back(scored[size_t(i)].second);
  return out;
}

// Pelli & Zhang: a grid over the whole box finds the basins, Levenberg–Marquardt from its four
// best points the optimum; the lowest of the four is the fit.
GammaFit fit_eq4(const std::vector<Reading>& r) {
  const double lo = r.front().luminance;
  const PelliZhangResiduals residuals{r};
  const ParameterBox<3> box{{0.8, 1e-5, 2.0}, {5.0, lo - 1e-5, 200.0}};
  ParameterVector<3> best = box.lower;
  double best_rss = std::numeric_limits<double>::infinity();
  for (ParameterVector<3> p : best_grid_points(residuals, box, 4)) {
    const double rss = minimize_within_box<3>(residuals, box, p).sum_of_squares;
    if (rss < best_rss) best_rss = rss, best = p;
  }
  const double g = best[0], a = best[1], k = best[2];
  return {"pelli-zhang",
          {{"gamma", g}, {"a", a}, {"k", k}, {"b", std::pow(lo - a, 1.0 / g)}},
          {},
          best_rss};
}

// The column called `name` (−1 if absent).
int column_of(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  return it == header.end() ? -1 : int(it - header.begin());
}

double number_at(const std::string& text, const std::string& where, const std::string& column) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    throw_input_error(where, column + ": expected a finite number, got '" + text + "'");
  return v;
}

// Each gun's readings must rise with the level, and be enough for three parameters.
void check_guns(const GunReadings& guns, const std::string& file) {
  if (guns.empty()) throw_input_error(file, "no readings");
  for (const auto& [gun, readings] : guns) {
    if (readings.size() < 4)
      throw_input_error(file, "gun " + gun + ": " + std::to_string(readings.size()) +
                                  " readings; at least 4 are needed to fit three parameters");
    for (size_t i = 1; i < readings.size(); ++i) {
      if (readings[i].level == readings[i - 1].level)
        throw_input_error(
            file, "gun " + gun + ": level " + std::to_string(readings[i].level) + " is read twice");
      if (readings[i].luminance <= readings[i - 1].luminance)
        throw_input_error(file, "gun " + gun + ": luminance does not rise with the level (" +
                                    std::to_string(readings[i].luminance) + " cd/m² at level " +
                                    std::to_string(readings[i].level) + " after " +
                                    std::to_string(readings[i - 1].luminance) + ")");
    }
  }
}

}  // namespace

namespace {

// The columns of a readings file; a level column may be missing (−1).
struct ReadingColumns {
  int gun = -1, lum = -1, code = -1, gl = -1;
};

// A level column's value on one row, checked against its range: code_value an integer from 0 to
// `top`, gl a number from 0 to 1. Returned in [0, 1].
double level_at(const std::vector<std::string>& row, int column, bool is_code, double top, int bits,
                const std::string& where) {
  const std::string name = is_code ? "code_value" : "gl";
  const std::string& text = row[size_t(column)];
  const double level = number_at(text, where, name);
  if (level < 0 || level > top || (is_code && level != std::floor(level)))
    throw_input_error(
        where,
        name + ": " + text + " is not a level from 0 to " +
            (is_code ? std::to_string(int(top)) + " (--bits " + std::to_string(bits) + ")" : "1"));
  return level / top;
}

// A row's level in [0, 1]: from code_value or gl, or from both when a photometer's export carries
// both, which must then agree (gl = code_value / (2^bits − 1) within 1e-6).
double row_level(const std::vector<std::string>& row, const ReadingColumns& c, int bits,
                 const std::string& where) {
  const double top = double((1u << bits) - 1u);
  if (c.gl < 0) return level_at(row, c.code, true, top, bits, where);
  const double gl = level_at(row, c.gl, false, 1.0, bits, where);
  if (c.code < 0) return gl;
  const double code = level_at(row, c.code, true, top, bits, where);
  if (std::abs(gl - code) > 1e-6)
    throw_input_error(where, "gl " + row[size_t(c.gl)] + " does not match code_value " +
                                 row[size_t(c.code)] + " (" + row[size_t(c.code)] + "/" +
                                 std::to_string(int(top)) + " = " + std::to_string(code) +
                                 " at --bits " + std::to_string(bits) + ")");
  return code;
}

}  // namespace

GunReadings read_photometer_readings(const std::filesystem::path& csv, int bits) {
  const std::string file = csv.string();
  const CsvTable table = parse_csv(read_file_bytes(csv), file);
  if (table.rows.empty()) throw_input_error(file, "empty file");
  const auto& header = table.rows[0];
  const ReadingColumns c{column_of(header, "gun"), column_of(header, "lum_cd_m2"),
                         column_of(header, "code_value"), column_of(header, "gl")};
  if (c.gun < 0 || c.lum < 0 || (c.code < 0 && c.gl < 0))
    throw_input_error(file, "expected the columns gun, lum_cd_m2 and code_value or gl (or both)");
  GunReadings out;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    const std::string where = file + ": line " + std::to_string(table.lines[r]);
    if (row.size() != header.size())
      throw_input_error(where, "expected " + std::to_string(header.size()) + " fields");
    const std::string& g = row[size_t(c.gun)];
    if (g != "R" && g != "G" && g != "B" && g != "W")
      throw_input_error(where, "gun: expected R, G, B or W, got '" + g + "'");
    const double level = row_level(row, c, bits, where);
    const double luminance = number_at(row[size_t(c.lum)], where, "lum_cd_m2");
    if (luminance < 0) throw_input_error(where, "lum_cd_m2: a luminance cannot be negative");
    out[g].push_back({level, luminance});
  }
  for (auto& [g, readings] : out)
    std::sort(readings.begin(), readings.end(),
              [](const Reading& a, const Reading& b) { return a.level < b.level; });
  check_guns(out, file);
  return out;
}

double GammaFit::predict(double x) const {
  const auto& p = params;
  if (model == "psyphy") return p.at("Blev") + p.at("k") * std::pow(x, p.at("gamm"));
  if (model == "psychopy-eq1") return p.at("a") + std::pow(p.at("b") * x, p.at("gamma"));
  if (model == "psychopy-eq2") return std::pow(p.at("a") + p.at("b") * x, p.at("gamma"));
  return p.at("a") + std::pow(p.at("b") + p.at("k") * x, p.at("gamma"));
}

std::vector<GammaFit> fit_gamma_models(const std::vector<Reading>& readings) {
  std::vector<GammaFit> out = {fit_psyphy(readings), fit_eq1(readings), fit_eq2(readings)};
  // Pelli & Zhang's a lies in [1e-5, L(0) − 1e-5]: a black level of (almost) zero leaves it no
  // room.
  if (readings.front().luminance > 2e-5) out.push_back(fit_eq4(readings));
  return out;
}

nlohmann::ordered_json fits_to_json(const std::map<std::string, std::vector<GammaFit>>& fits) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const auto& [gun, models] : fits)
    for (const GammaFit& f : models) {
      nlohmann::ordered_json j = nlohmann::ordered_json::object();
      for (const auto& [name, value] : f.params) j[name] = value;
      if (!f.se.empty()) j["se"] = f.se;
      j["rss"] = f.rss;
      out[gun][f.model] = j;
    }
  return out;
}

std::string lookup_table_csv(const std::vector<const GammaFit*>& fits, int bits) {
  const uint32_t top = (1u << bits) - 1u;
  std::string out = "code,luminance\n";
  double previous = -std::numeric_limits<double>::infinity();
  char line[64];
  for (uint32_t code = 0; code <= top; ++code) {
    double luminance = 0;
    for (const GammaFit* f : fits) luminance += f->predict(double(code) / double(top));
    if (!(luminance > previous))
      throw InputError("the fitted luminance does not rise at code " + std::to_string(code) +
                       ": the readings cannot make a lookup table");
    previous = luminance;
    std::snprintf(line, sizeof line, "%u,%.17g\n", code, luminance);
    out += line;
  }
  return out;
}

}  // namespace countershade::analysis
