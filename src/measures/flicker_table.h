#pragma once
// The `flicker` command's report: one CSV row per frame pair (the columns depend on the options
// measured, docs/enhancement-methods.md "Flicker"), and a one-line summary of the means over
// pairs.

#include <string>

#include "measures/flicker.h"

namespace countershade {

class FlickerTable {
 public:
  explicit FlickerTable(const FlickerOptions& options);
  void add(int frame, const PlainChange& plain, const PairFlicker& pair);
  const std::string& csv() const { return csv_; }
  size_t pixels() const { return pixels_; }  // over every pair: 0 means nothing was measured
  // `object`: the name of FlickerOptions::object; `component`: what was measured ("layer", "mask").
  std::string summary(const std::string& object, const std::string& component = "layer") const;

 private:
  const FlickerOptions& o_;
  std::string csv_;
  double mean_[8] = {};  // sums over pairs: layer, plain, both at scale, stable, stable share,
                         // region, plain there
  ObjectChange object_, object_stable_;  // the worst pair's
  int pairs_ = 0;
  size_t pixels_ = 0;
};

}  // namespace countershade
