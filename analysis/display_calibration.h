#pragma once
// Display calibration from photometer readings (docs/display.md): per gun, the gamma models that
// psychophysics software fits, by least squares on luminance, and the display's lookup table.
//
//   psyphy        L = Blev + k·x^gamm                          (R psyphy's SS.calib)
//   psychopy-eq1  L = a + (b·x)^γ, a = L(0), b = (L(1) − a)^(1/γ)   (PsychoPy's eq. 1)
//   psychopy-eq2  L = (a + b·x)^γ, a = L(0)^(1/γ), b = L(1)^(1/γ) − a   (eq. 2)
//   pelli-zhang   L = a + (b + k·x)^γ, b = (L(0) − a)^(1/γ)      (eq. 4, Pelli & Zhang 1991)
//
// x is the level in [0, 1]; L(0) and L(1) are the gun's readings at x = 0 and 1. γ of the PsychoPy
// models lies in [0.8, 5], and pelli-zhang's a in [1e-5, L(0) − 1e-5], k in [2, 200], PsychoPy's
// bounds. Each fit is the least-squares optimum, found by nested one-dimensional searches over the
// nonlinear parameters (the linear ones solved exactly), so it does not depend on a start value.

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace countershade::analysis {

struct Reading {
  double level = 0;      // x in [0, 1]
  double luminance = 0;  // cd/m²
};

// A gun's readings, sorted by level: R, G, B, or W (white or grey: all three guns).
using GunReadings = std::map<std::string, std::vector<Reading>>;

// Reads a CSV with the columns gun, level as `code_value` (0 … 2^bits − 1) or `gl` (0 … 1), and
// lum_cd_m2. Refuses (InputError, naming the file and line) a missing column, a gun other than
// R, G, B, W, a level out of range, a negative or non-finite luminance, a repeated level, fewer
// than 4 readings of a gun (3 parameters and one degree of freedom), and luminance that does not
// rise with the level.
GunReadings read_photometer_readings(const std::filesystem::path& csv, int bits);

struct GammaFit {
  std::string model;  // psyphy, psychopy-eq1, psychopy-eq2, pelli-zhang
  std::map<std::string, double>
      params;  // under the reference names: psyphy Blev, k, gamm; others gamma, a, b (k)
  std::map<std::string, double> se;    // psyphy only: standard errors as R's nls gives them
  double rss = 0;                      // residual sum of squares, (cd/m²)²
  double predict(double level) const;  // L at a level
};

// Every model's fit of one gun's readings.
std::vector<GammaFit> fit_gamma_models(const std::vector<Reading>& readings);

// The fits of every gun, as DISPLAY.json's `fits` holds them: gun → model → parameters and rss.
nlohmann::ordered_json fits_to_json(const std::map<std::string, std::vector<GammaFit>>& fits);

// The display's lookup table as the scene format reads it (docs/scene-format.md, `lut`): a row
// `code,luminance` for every code value 0 … 2^bits − 1, the luminance in cd/m² from `fit` (the
// white gun's psyphy fit, or the sum of R, G and B). Throws InputError if the luminance does not
// rise strictly from code to code.
std::string lookup_table_csv(const std::vector<const GammaFit*>& fits, int bits);

}  // namespace countershade::analysis
