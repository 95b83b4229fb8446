#include "stimuli/headroom.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "enhance/method.h"
#include "stimuli/audit.h"
#include "stimuli/mean_hold.h"

namespace countershade {

double headroom_stops(const ClippedAt& clipped_at, double limit, double resolution, double floor, double ceiling) {
  const Clipped start = clipped_at(0.0);
  // Within the limit, nothing to do; over it at both ends, no exposure helps one without the other.
  if (start.within(limit) || (start.white > limit && start.black > limit)) return 0.0;
  const double direction = start.white > limit ? -1.0 : 1.0, end = direction < 0 ? floor : ceiling;
  auto leading = [&](const Clipped& c) { return direction < 0 ? c.white : c.black; };  // the share the move is after
  auto other = [&](const Clipped& c) { return direction < 0 ? c.black : c.white; };
  double share = leading(start), failing = 0.0, passing = 0.25 * direction;
  for (Clipped c; !(c = clipped_at(passing)).within(limit); share = leading(c)) {
    // A share that does not fall as the exposure moves, or the other end now over the limit
    // (moving on would only add to it): nothing to gain.
    if (leading(c) >= share || other(c) > limit || passing == end) return failing;
    failing = passing;
    passing = direction < 0 ? std::max(2 * passing, end) : std::min(2 * passing, end);
  }
  while (std::abs(failing - passing) > resolution) {
    const double middle = 0.5 * (failing + passing);
    (clipped_at(middle).within(limit) ? passing : failing) = middle;
  }
  return passing;
}

namespace {

std::vector<uint16_t> codes_of(const Image& display, int bits) {
  std::vector<uint16_t> codes(display.pixels.size());
  for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint16_t(quantize(display.pixels[i], bits));
  return codes;
}

// The shares of pixels the enhancement clipped at full scale and at black.
Clipped clipped_shares(const std::vector<uint16_t>& stimulus, const std::vector<uint16_t>& reference, int bits) {
  const uint16_t top = uint16_t((1u << bits) - 1u);
  size_t white = 0, black = 0;
  for (size_t p = 0; 3 * p < stimulus.size(); ++p) {
    const uint16_t *s = &stimulus[3 * p], *r = &reference[3 * p];
    if (!clipped_by_enhancement(s, r, top)) continue;
    bool at_top = false, at_zero = false;
    for (int k = 0; k < 3; ++k) at_top |= s[k] == top && r[k] != top, at_zero |= s[k] == 0 && r[k] != 0;
    white += at_top;
    black += at_zero && !at_top;
  }
  const double n = std::max<double>(1.0, double(stimulus.size() / 3));
  return {double(white) / n, double(black) / n};
}

}  // namespace

Clipped largest_clipped(const std::shared_ptr<const View>& view, const std::vector<double>& lambdas, int threads,
                        bool hold_mean) {
  const std::vector<uint16_t> reference = codes_of(view->display, view->bits);
  Clipped largest;
  for (size_t use = 0; use < view->uses.size(); ++use) {
    const MethodUse& u = view->uses[use];
    if (!u.method->enhances()) continue;
    PrepareContext context = make_use_context(view, use, threads);
    context.compose_from_samples = true;
    const auto prepared = u.method->prepare(context, *u.parameters);
    for (double lambda : lambdas) {
      Image display = prepared->compose(lambda).display;
      if (hold_mean) display = hold_mean_lightness(*view, display).display;
      const Clipped c = clipped_shares(codes_of(display, view->bits), reference, view->bits);
      largest = {std::max(largest.white, c.white), std::max(largest.black, c.black)};
    }
  }
  return largest;
}

}  // namespace countershade
