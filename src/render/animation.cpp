#include "render/animation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace countershade {

Track::Track(std::vector<double> times, std::vector<glm::dvec3> values, Interpolation mode)
    : times_(std::move(times)), values_(std::move(values)), mode_(mode) {
  if (times_.size() != values_.size()) throw std::invalid_argument("needs as many values as times");
  if (times_.size() < 2) throw std::invalid_argument("a path needs at least two keys");
  for (size_t i = 1; i < times_.size(); ++i)
    if (!(times_[i] > times_[i - 1]))
      throw std::invalid_argument("times must increase strictly (key " + std::to_string(i + 1) +
                                  ")");
}

glm::dvec3 Track::tangent(size_t key) const {
  const size_t before = key == 0 ? 0 : key - 1, after = std::min(key + 1, times_.size() - 1);
  return (values_[after] - values_[before]) / (times_[after] - times_[before]);
}

glm::dvec3 Track::at(double time) const {
  if (time <= times_.front()) return values_.front();
  if (time >= times_.back()) return values_.back();
  const size_t k =
      size_t(std::upper_bound(times_.begin(), times_.end(), time) - times_.begin()) - 1;
  const double h = times_[k + 1] - times_[k], s = (time - times_[k]) / h;
  if (s == 0.0) return values_[k];  // exactly the key
  if (mode_ == Interpolation::linear) return values_[k] + s * (values_[k + 1] - values_[k]);
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * values_[k] + (s3 - 2 * s2 + s) * h * tangent(k) +
         (-2 * s3 + 3 * s2) * values_[k + 1] + (s3 - s2) * h * tangent(k + 1);
}

int Animation::frame_count() const { return std::max(1, int(std::floor(duration * fps + 1e-9))); }

}  // namespace countershade
