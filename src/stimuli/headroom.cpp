#include "stimuli/headroom.h"

#include <algorithm>
#include <cstdint>

#include "enhance/method.h"
#include "stimuli/audit.h"
#include "stimuli/mean_hold.h"

namespace countershade {

double headroom_stops(const ClippedAt& clipped_at, double limit, double resolution, double floor) {
  double share = clipped_at(0.0);
  if (share <= limit) return 0.0;
  double failing = 0.0, passing = -0.25;
  for (double lower; (lower = clipped_at(passing)) > limit; share = lower) {
    // A share that does not fall with the exposure is not clipping at the top: nothing to gain.
    if (lower >= share || passing <= floor) return failing;
    failing = passing;
    passing = std::max(2 * passing, floor);
  }
  while (failing - passing > resolution) {
    const double middle = 0.5 * (failing + passing);
    (clipped_at(middle) <= limit ? passing : failing) = middle;
  }
  return passing;
}

namespace {

std::vector<uint16_t> codes_of(const Image& display, int bits) {
  std::vector<uint16_t> codes(display.pixels.size());
  for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint16_t(quantize(display.pixels[i], bits));
  return codes;
}

// The share of pixels the enhancement clipped at full scale. Clipping at black (a darkening
// operator's) does not shrink with the exposure, so it is left to the audit.
double clipped_share(const std::vector<uint16_t>& stimulus, const std::vector<uint16_t>& reference, int bits) {
  const uint16_t top = uint16_t((1u << bits) - 1u);
  size_t clipped = 0;
  for (size_t p = 0; 3 * p < stimulus.size(); ++p) {
    const uint16_t *s = &stimulus[3 * p], *r = &reference[3 * p];
    bool at_top = false;
    for (int k = 0; k < 3; ++k) at_top |= s[k] == top && r[k] != top;
    clipped += at_top && clipped_by_enhancement(s, r, top);
  }
  return stimulus.empty() ? 0.0 : double(clipped) / double(stimulus.size() / 3);
}

}  // namespace

double largest_clipped_share(const std::shared_ptr<const View>& view, const std::vector<double>& lambdas, int threads,
                             bool hold_mean) {
  const std::vector<uint16_t> reference = codes_of(view->display, view->bits);
  double largest = 0;
  for (size_t use = 0; use < view->uses.size(); ++use) {
    const MethodUse& u = view->uses[use];
    if (!u.method->enhances()) continue;
    PrepareContext context = make_use_context(view, use, threads);
    context.compose_from_samples = true;
    const auto prepared = u.method->prepare(context, *u.parameters);
    for (double lambda : lambdas) {
      Image display = prepared->compose(lambda).display;
      if (hold_mean) display = hold_mean_lightness(*view, display).display;
      largest = std::max(largest, clipped_share(codes_of(display, view->bits), reference, view->bits));
    }
  }
  return largest;
}

}  // namespace countershade
