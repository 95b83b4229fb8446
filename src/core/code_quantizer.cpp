#include "core/code_quantizer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "core/image.h"

namespace countershade {
namespace {

// Values below 2^-kLowestExponent all have code 0 (checked when the table is built).
constexpr int kLowestExponent = 30;

double clamp_unit(double x) { return std::isnan(x) ? 0.0 : std::clamp(x, 0.0, 1.0); }

// The buckets as CodeQuantizer::Table::packed words (codes of up to 16 bits, at least 6 mantissa
// bits per bucket, so the threshold's low bits stay below kNoThreshold).
std::vector<uint64_t> pack_buckets(const std::vector<CodeQuantizer::Bucket>& buckets, int shift) {
  if (shift > 46) throw std::logic_error("CodeQuantizer: buckets too wide to pack");
  std::vector<uint64_t> packed(buckets.size());
  const uint64_t low = (uint64_t(1) << shift) - 1;
  for (size_t b = 0; b < buckets.size(); ++b) {
    const double t = buckets[b].threshold;
    const uint64_t threshold =
        std::isinf(t) ? CodeQuantizer::kNoThreshold : std::bit_cast<uint64_t>(t) & low;
    if (buckets[b].below > 0xFFFFu)
      throw std::logic_error("CodeQuantizer: a code too large to pack");
    packed[b] = uint64_t(buckets[b].below) << 48 | threshold;
  }
  return packed;
}

}  // namespace

uint32_t CodeQuantizer::exact_code(double linear) const {
  return quantize(float(encoding_.encode(linear)), bits_);
}

CodeQuantizer::CodeQuantizer(const DisplayEncoding& encoding, int bits)
    : encoding_(encoding), bits_(bits), levels_(float((1u << bits) - 1u)) {
  const uint32_t max_code = (1u << bits) - 1u;
  thresholds_.assign(size_t(max_code) + 1, 0.0);
  // Threshold k by bisection: the smallest double x with exact_code(x) ≥ k (codes rise with x).
  for (uint32_t k = 1; k <= max_code; ++k) {
    double lo = thresholds_[k - 1], hi = 1.0;
    if (exact_code(hi) < k) {  // unreachable code (a flat encoding): never given
      thresholds_[k] = std::numeric_limits<double>::infinity();
      continue;
    }
    while (std::nextafter(lo, 2.0) < hi) {
      const double mid = lo + (hi - lo) / 2;
      (exact_code(mid) >= k ? hi : lo) = mid;
    }
    thresholds_[k] = exact_code(lo) >= k ? lo : hi;
  }
  code_at_zero_ = exact_code(0.0);
  code_at_one_ = exact_code(1.0);
  for (int m = 6; m <= 10 && !mantissa_bits_; ++m)
    if (build_table(m)) mantissa_bits_ = m;
}

bool CodeQuantizer::build_table(int m) {
  const size_t buckets = size_t(kLowestExponent) << m;
  const uint64_t first = uint64_t(1023 - kLowestExponent) << m;
  if (exact_code(std::ldexp(1.0, -kLowestExponent)) != exact_code(0.0)) return false;
  std::vector<Bucket> table(buckets + 1);
  for (size_t b = 0; b < buckets; ++b) {
    const double lo = std::bit_cast<double>((first + b) << (52 - m));
    const double hi = std::bit_cast<double>((first + b + 1) << (52 - m));
    const uint32_t low = exact_code(lo), high = exact_code(std::nextafter(hi, 0.0));
    if (high > low + 1) return false;  // two thresholds in one bucket: more mantissa bits
    table[b] = {high > low ? thresholds_[high] : std::numeric_limits<double>::infinity(), low};
  }
  table[buckets] = {std::numeric_limits<double>::infinity(), exact_code(1.0)};  // x = 1
  buckets_ = std::move(table);
  packed_ = pack_buckets(buckets_, 52 - m);
  return true;
}

CodeQuantizer::Table CodeQuantizer::table() const {
  Table t;
  t.shift = 52 - mantissa_bits_;
  t.offset = int64_t(1023 - kLowestExponent) << mantissa_bits_;
  t.last = int64_t(buckets_.size()) - 1;
  t.bucket = buckets_.data();
  t.packed = packed_.data();
  return t;
}

const CodeQuantizer& CodeQuantizer::shared(const DisplayEncoding& encoding, int bits) {
  static std::mutex mutex;
  static std::vector<std::unique_ptr<CodeQuantizer>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& q : cache)
    if (q->bits_ == bits && q->encoding_ == encoding) return *q;
  cache.push_back(std::make_unique<CodeQuantizer>(encoding, bits));
  return *cache.back();
}

uint32_t CodeQuantizer::search(double x) const {
  return uint32_t(std::upper_bound(thresholds_.begin() + 1, thresholds_.end(), x) -
                  thresholds_.begin()) -
         1;
}

uint32_t CodeQuantizer::code(double linear) const {
  const double x = clamp_unit(linear);
  if (!mantissa_bits_) return search(x);
  const Table t = table();
  const int64_t b =
      std::clamp(int64_t(std::bit_cast<uint64_t>(x) >> t.shift) - t.offset, int64_t(0), t.last);
  return t.bucket[b].below + uint32_t(x >= t.bucket[b].threshold);
}

}  // namespace countershade
