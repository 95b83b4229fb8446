#include "stimuli/headroom.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "enhance/method.h"
#include "stimuli/audit_limits.h"
#include "stimuli/mean_hold.h"

namespace countershade {

namespace {

// A setting tried and what the conditions clip at it.
struct Tried {
  double value = 0;
  Clipped clipped;
};

// The share a search is after: white clipping alone, or both ends together.
double share_of(const Clipped& c, bool total) { return total ? c.total() : c.white; }

// One setting's search from `start` (the setting at 0) against white clipping or the total. With
// `guard_white`, a step that clips more white than the start and more than the limit ends it.
Tried search_setting(const std::function<Clipped(double)>& at, const Tried& start,
                     const HeadroomSearch& search, bool total, double limit, bool guard_white) {
  auto spoils_white = [&](const Clipped& c) {
    return guard_white && c.white > std::max(limit, start.clipped.white);
  };
  auto passes = [&](const Clipped& c) { return share_of(c, total) <= limit && !spoils_white(c); };
  Tried failing = start, passing{search.first, at(search.first)};
  while (!passes(passing.clipped)) {
    // A share that does not fall as the setting moves, white spoilt, or the end: nothing to gain.
    const bool stalled = share_of(passing.clipped, total) >= share_of(failing.clipped, total);
    if (stalled || spoils_white(passing.clipped) || passing.value == search.end) return failing;
    failing = passing;
    const double next = search.first > 0 ? std::min(2 * passing.value, search.end)
                                         : std::max(2 * passing.value, search.end);
    passing = {next, at(next)};
  }
  while (std::abs(failing.value - passing.value) > search.resolution) {
    const double middle = 0.5 * (failing.value + passing.value);
    const Tried tried{middle, at(middle)};
    (passes(tried.clipped) ? passing : failing) = tried;
  }
  return passing;
}

}  // namespace

Headroom find_headroom(const ClippedAt& clipped_at, double limit, const HeadroomSearch& exposure,
                       const HeadroomSearch& black_level) {
  Tried stops{0.0, clipped_at({})};
  if (stops.clipped.white > limit)
    stops = search_setting(
        [&](double s) {
          return clipped_at({s, 0.0});
        },
        stops, exposure, false, limit, false);
  Tried black{0.0, stops.clipped};
  if (black.clipped.total() > limit && black.clipped.black > 0)
    black = search_setting(
        [&](double b) {
          return clipped_at({stops.value, b});
        },
        black, black_level, true, limit, true);
  return {stops.value, black.value};
}

namespace {

std::vector<uint16_t> codes_of(const Image& display, int bits) {
  std::vector<uint16_t> codes(display.pixels.size());
  for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint16_t(quantize(display.pixels[i], bits));
  return codes;
}

// The shares of pixels the enhancement clipped at full scale and at black.
Clipped clipped_shares(const std::vector<uint16_t>& stimulus,
                       const std::vector<uint16_t>& reference, int bits) {
  const uint16_t top = uint16_t((1u << bits) - 1u);
  size_t white = 0, black = 0;
  for (size_t p = 0; 3 * p < stimulus.size(); ++p) {
    const uint16_t *s = &stimulus[3 * p], *r = &reference[3 * p];
    if (!clipped_by_enhancement(s, r, top)) continue;
    bool at_top = false, at_zero = false;
    for (int k = 0; k < 3; ++k)
      at_top |= s[k] == top && r[k] != top, at_zero |= s[k] == 0 && r[k] != 0;
    white += at_top;
    black += at_zero && !at_top;
  }
  const double n = std::max<double>(1.0, double(stimulus.size() / 3));
  return {double(white) / n, double(black) / n};
}

}  // namespace

Clipped largest_clipped(const std::shared_ptr<const View>& view, const std::vector<double>& lambdas,
                        int threads, bool hold_mean) {
  const std::vector<uint16_t> reference = codes_of(view->display, view->bits);
  Clipped largest{0, 0, 0};
  for (size_t use = 0; use < view->uses.size(); ++use) {
    const MethodUse& u = view->uses[use];
    if (!u.method->enhances()) continue;
    PrepareContext context = make_use_context(view, use, threads);
    context.compose_from_samples = true;
    const auto prepared = u.method->prepare(context, *u.parameters);
    for (double lambda : lambdas) {
      Image display = prepared->compose(lambda).display;
      if (hold_mean) display = hold_mean_lightness(*view, *prepared, lambda, {display, 0}).display;
      const Clipped c = clipped_shares(codes_of(display, view->bits), reference, view->bits);
      largest = {std::max(largest.white, c.white), std::max(largest.black, c.black),
                 std::max(largest.total(), c.total())};
    }
  }
  return largest;
}

}  // namespace countershade
