#include "measures/flicker_table.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace countershade {
namespace {

void keep_worst(ObjectChange& worst, const ObjectChange& change) {
  worst.max = std::max(worst.max, change.max);
  worst.p99 = std::max(worst.p99, change.p99);
}

}  // namespace

FlickerTable::FlickerTable(const FlickerOptions& o) : o_(o) {
  csv_ = "frame,flicker_lstar,plain_reprojection_lstar,pixels";
  if (o.scale_px > 0) csv_ += ",flicker_at_scale_lstar,plain_at_scale_lstar";
  if (o.stable > 0) csv_ += ",flicker_stable_lstar,stable_pixels";
  if (o.object >= 0) csv_ += ",object_max_levels,object_p99_levels,object_pixels";
  if (o.object >= 0 && o.stable > 0)
    csv_ += ",object_stable_max_levels,object_stable_p99_levels,object_stable_pixels";
  if (o.has_region()) csv_ += ",region_lstar,plain_region_lstar,region_pixels";
  csv_ += '\n';
}

void FlickerTable::add(int frame, const PlainChange& plain, const PairFlicker& p) {
  std::ostringstream row;
  row << frame << ',' << p.layer.rms << ',' << plain.rms.rms << ',' << p.layer.pixels;
  if (o_.scale_px > 0) row << ',' << p.at_scale << ',' << p.plain_at_scale;
  if (o_.stable > 0) row << ',' << p.stable.rms << ',' << p.stable.pixels;
  if (o_.object >= 0) row << ',' << p.object.max << ',' << p.object.p99 << ',' << p.object.pixels;
  if (o_.object >= 0 && o_.stable > 0)
    row << ',' << p.object_stable.max << ',' << p.object_stable.p99 << ','
        << p.object_stable.pixels;
  if (o_.has_region())
    row << ',' << p.region.rms << ',' << p.plain_region.rms << ',' << p.region.pixels;
  csv_ += row.str() + '\n';
  const double share = p.layer.pixels ? double(p.stable.pixels) / double(p.layer.pixels) : 0.0;
  const double values[] = {p.layer.rms,  plain.rms.rms, p.at_scale,   p.plain_at_scale,
                           p.stable.rms, share,         p.region.rms, p.plain_region.rms};
  for (size_t k = 0; k < std::size(values); ++k) mean_[k] += values[k];
  keep_worst(object_, p.object);
  keep_worst(object_stable_, p.object_stable);
  ++pairs_;
  pixels_ += p.layer.pixels;
}

std::string FlickerTable::summary(const std::string& object, const std::string& component) const {
  const auto m = [&](int k) { return mean_[k] / pairs_; };
  char line[320];
  const std::string what = component == "layer" ? "flicker" : component + " flicker";
  std::snprintf(line, sizeof line,
                "%d frame pairs, mean %s %.4f L* (the plain render's own reprojection %.4f L*)",
                pairs_, what.c_str(), m(0), m(1));
  std::string out = line;
  if (o_.has_region()) {
    std::snprintf(line, sizeof line, "; in the region: %.4f L* (plain %.4f L*)", m(6), m(7));
    out += line;
  }
  if (o_.scale_px > 0) {
    std::snprintf(line, sizeof line, "; at %g px: %.4f L* (plain %.4f L*)", o_.scale_px, m(2),
                  m(3));
    out += line;
  }
  if (o_.stable > 0) {
    std::snprintf(line, sizeof line,
                  "; where the plain L* reprojects within %g: %.4f L* (%.0f %% of the pixels)",
                  o_.stable, m(4), 100.0 * m(5));
    out += line;
  }
  if (o_.object < 0) return out;
  std::snprintf(line, sizeof line, "; %s: largest change %.2f code levels (p99 %.2f, worst pair)",
                object.c_str(), object_.max, object_.p99);
  out += line;
  if (o_.stable > 0) {
    std::snprintf(line, sizeof line, ", where stable %.2f (p99 %.2f)", object_stable_.max,
                  object_stable_.p99);
    out += line;
  }
  return out;
}

}  // namespace countershade
