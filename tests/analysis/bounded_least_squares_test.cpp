// The analysis's bounded Levenberg–Marquardt (analysis/bounded_least_squares.h) against closed
// forms: a straight line free and with its slope on a bound, and an exponential decay from a
// start far from it.

#include "analysis/bounded_least_squares.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace countershade::analysis {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// y = p0 + p1·x through the points.
struct Line {
  std::vector<double> x, y;
  int count() const { return int(x.size()); }
  template <class T>
  void operator()(const T* p, T* r) const {
    for (size_t i = 0; i < x.size(); ++i) r[i] = p[0] + p[1] * x[i] - T(y[i]);
  }
};

const Line kPoints{{0, 1, 2, 3, 4, 5}, {1.1, 2.9, 5.2, 7.1, 8.8, 11.3}};

TEST(BoundedLeastSquares, AFreeLineIsTheNormalEquationsSolution) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < kPoints.x.size(); ++i) {
    const double x = kPoints.x[i], y = kPoints.y[i];
    n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx), intercept = (sy - slope * sx) / n;
  ParameterVector<2> p(0.0, 0.0);
  const ParameterBox<2> box{{-kInfinity, -kInfinity}, {kInfinity, kInfinity}};
  const LeastSquaresResult result = minimize_within_box<2>(kPoints, box, p);
  // The solver stops where the sum (0.17 here) no longer changes in double precision: about
  // 1e-8 · √(0.17 / Σx²) ≈ 1e-9 from the optimum at most.
  EXPECT_NEAR(p[0], intercept, 1e-9);
  EXPECT_NEAR(p[1], slope, 1e-9);
  EXPECT_TRUE(result.finite);
  EXPECT_NEAR(result.sum_of_squares, sum_of_squares<2>(kPoints, p), 1e-15);
}

// The free slope is about 2; held at most 1.5 it sits on the bound, and the intercept is the
// mean of y − 1.5·x, the optimum for that slope.
TEST(BoundedLeastSquares, ASlopeOnItsBoundStaysThereAndTheRestIsOptimal) {
  ParameterVector<2> p(0.0, 1.0);
  const ParameterBox<2> box{{-kInfinity, -kInfinity}, {kInfinity, 1.5}};
  minimize_within_box<2>(kPoints, box, p);
  double mean = 0;
  for (size_t i = 0; i < kPoints.x.size(); ++i) mean += kPoints.y[i] - 1.5 * kPoints.x[i];
  mean /= double(kPoints.x.size());
  EXPECT_EQ(p[1], 1.5);
  EXPECT_NEAR(p[0], mean, 1e-9);
}

// y = p0·exp(−p1·x), exact data.
struct Decay {
  int count() const { return 8; }
  template <class T>
  void operator()(const T* p, T* r) const {
    using std::exp;
    for (int i = 0; i < 8; ++i)
      r[i] = p[0] * exp(-p[1] * (double(i) / 2.0)) - 3.0 * std::exp(-0.7 * double(i) / 2.0);
  }
};

TEST(BoundedLeastSquares, AnExponentialDecayIsRecoveredFromAFarStart) {
  ParameterVector<2> p(0.5, 5.0);
  const ParameterBox<2> box{{0.0, 0.0}, {100.0, 10.0}};
  const LeastSquaresResult result = minimize_within_box<2>(Decay{}, box, p);
  EXPECT_NEAR(p[0], 3.0, 1e-10);
  EXPECT_NEAR(p[1], 0.7, 1e-10);
  EXPECT_LT(result.sum_of_squares, 1e-20);
}

}  // namespace
}  // namespace countershade::analysis
