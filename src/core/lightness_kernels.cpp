#include "core/lightness_kernels.h"

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <type_traits>

#include "core/isa.h"
#include "core/lane_math.h"

namespace countershade {

namespace {

using v4d = NarrowLanes;
using v4l = NarrowLaneBits;
using v8d = double __attribute__((vector_size(64)));
using v8l = int64_t __attribute__((vector_size(64)));
using v4f = float __attribute__((vector_size(16)));
using v8f = float __attribute__((vector_size(32)));
using v8i = int32_t __attribute__((vector_size(32)));

// lab_to_linear_rgb(with_lightness(lab, target)) on four or eight pixels: the same operations in
// the same order as the scalar functions of core/color.h, lane by lane, so the results are
// identical.
template <typename D>
struct RgbLanes {
  D r, g, b;
};
// Vectors go by reference in and out of these helpers: clang refuses 512-bit vectors passed or
// returned by value in a function compiled without AVX-512, even when it is inlined into one with
// it. CIELAB's inverse f times a white component.
template <typename D>
[[gnu::always_inline]] inline void lab_f_inverse_lanes(const D& t, double white, D& out) {
  out = (t > 0.2068966 ? t * t * t : (t - 16.0 / 116.0) * color_constants::k1_7787) * white;
}
template <typename D>
[[gnu::always_inline]] inline RgbLanes<D> lightness_to_rgb(const D& L, const D& a, const D& b,
                                                           const D& target) {
  using namespace color_constants;
  const auto& m = kXyzToRgb.m;
  const D Lc = target < 0.0 ? 0.0 : (target > 100.0 ? 100.0 : target);
  const D k = L < 1e-6 ? 1.0 : Lc / L;
  const D fy = (Lc + 16.0) * k1_116;
  const D fx = (k * a) * k1_500 + fy;
  const D fz = fy - (k * b) * k1_200;
  D X, Y, Z;
  lab_f_inverse_lanes(fx, kWhite[0], X);
  lab_f_inverse_lanes(fy, kWhite[1], Y);
  lab_f_inverse_lanes(fz, kWhite[2], Z);
  return {m[0][0] * X + m[0][1] * Y + m[0][2] * Z, m[1][0] * X + m[1][1] * Y + m[1][2] * Z,
          m[2][0] * X + m[2][1] * Y + m[2][2] * Z};
}
struct Rgb4 {
  v4d r, g, b;
  v4l clipped;  // the target outside [0, 100] or a channel outside [0, 1] (beyond round-off)
};
[[gnu::always_inline]] inline Rgb4 lightness_to_rgb4(v4d L, v4d a, v4d b, v4d target) {
  const RgbLanes<v4d> rgb = lightness_to_rgb(L, a, b, target);
  Rgb4 out{rgb.r, rgb.g, rgb.b, (target < 0.0) | (target > 100.0)};
  for (const v4d* c : {&out.r, &out.g, &out.b}) out.clipped |= (*c < -1e-9) | (*c > 1.0 + 1e-9);
  return out;
}

// The bucket of four linear values clamped to [0,1] (see CodeQuantizer::Table).
[[gnu::always_inline]] inline v4l bucket4(v4d x, const CodeQuantizer::Table& table) {
  v4l bucket = (__builtin_bit_cast(v4l, x) >> table.shift) - table.offset;
  return bucket < 0 ? 0 : (bucket > table.last ? table.last : bucket);
}

[[gnu::always_inline]] inline v4d clamp_unit4(v4d c) { return c < 0.0 ? 0.0 : (c > 1.0 ? 1.0 : c); }

// The code values of four pixels through the quantizer's table, as values in [0,1]: one lookup
// per lane and channel. Written with small arrays for the clamped values and their buckets: about
// 4 % faster than reading the lanes of the vectors directly (A/B, docs/performance.md), although
// GCC keeps both in registers.
[[gnu::always_inline]] inline void quantize_rgb4(const Rgb4& rgb, const CodeQuantizer::Table& table,
                                                 double inverse_levels, float* out) {
  alignas(32) double x[3][4];
  alignas(32) int64_t bucket[3][4];
  const v4d channels[3] = {rgb.r, rgb.g, rgb.b};
  for (int ch = 0; ch < 3; ++ch) {
    const v4d clamped = clamp_unit4(channels[ch]);
    std::memcpy(x[ch], &clamped, sizeof clamped);
    const v4l b = bucket4(clamped, table);
    std::memcpy(bucket[ch], &b, sizeof b);
  }
  uint32_t codes[12];  // RGBRGBRGBRGB
  for (int lane = 0; lane < 4; ++lane)
    for (int ch = 0; ch < 3; ++ch) {
      const CodeQuantizer::Bucket& b = table.bucket[bucket[ch][lane]];
      codes[3 * lane + ch] = b.below + uint32_t(x[ch][lane] >= b.threshold);
    }
  for (int i = 0; i < 12; ++i) out[i] = code_fraction(codes[i], inverse_levels);
}

// One block of pixels, four at a time: the lightness-only change and the code values. Pixels
// with Δ = 0 keep the view's code values. Returns the number of clipped pixels. The same code is
// compiled for AVX2 and for any x86-64 (chosen at run time); with no fused multiply-adds both
// give the same bits. (AVX2 gathers of four lanes were tried for the table lookups: slower here.)
template <void (*Quantize)(const Rgb4&, const CodeQuantizer::Table&, double, float*)>
[[gnu::always_inline]] inline size_t compose_block(const Lab* lab, const float* in,
                                                   const double* delta, size_t count,
                                                   const CodeQuantizer::Table& table,
                                                   double inverse_levels, float* out) {
  size_t clipped = 0;
  for (size_t k = 0; k + 4 <= count; k += 4) {
    float* o = out + 3 * k;
    if (delta[k] == 0.0 && delta[k + 1] == 0.0 && delta[k + 2] == 0.0 && delta[k + 3] == 0.0) {
      std::copy(in + 3 * k, in + 3 * k + 12, o);  // four unchanged pixels (background, λ = 0)
      continue;
    }
    // Four Lab pixels are 12 consecutive doubles: three loads, then L, a and b by shuffles.
    v4d v0, v1, v2, d;
    std::memcpy(&v0, &lab[k], sizeof v0);
    std::memcpy(&v1, reinterpret_cast<const double*>(&lab[k]) + 4, sizeof v1);
    std::memcpy(&v2, reinterpret_cast<const double*>(&lab[k]) + 8, sizeof v2);
    std::memcpy(&d, delta + k, sizeof d);
    const v4d L =
        __builtin_shufflevector(__builtin_shufflevector(v0, v1, 0, 3, 6, 6), v2, 0, 1, 2, 5);
    const v4d a =
        __builtin_shufflevector(__builtin_shufflevector(v0, v1, 1, 4, 7, 7), v2, 0, 1, 2, 6);
    const v4d b =
        __builtin_shufflevector(__builtin_shufflevector(v0, v1, 2, 5, 5, 5), v2, 0, 1, 4, 7);
    const Rgb4 rgb = lightness_to_rgb4(L, a, b, L + d);
    Quantize(rgb, table, inverse_levels, o);
    for (int lane = 0; lane < 4; ++lane) {
      if (d[lane] == 0.0)
        std::copy(in + 3 * (k + lane), in + 3 * (k + lane) + 3, o + 3 * lane);
      else
        clipped += rgb.clipped[lane] != 0;
    }
  }
  return clipped;
}

COUNTERSHADE_CLONES
size_t compose_block_fast(const Lab* lab, const float* in, const double* delta, size_t count,
                          const CodeQuantizer::Table& table, double inverse_levels, float* out) {
  return compose_block<quantize_rgb4>(lab, in, delta, count, table, inverse_levels, out);
}

// Eight pixels at a time with AVX-512, for machines that have it: the colour by the same
// operations as compose_block's, then each channel's eight codes through one gather from the
// quantizer's packed words, so no lane leaves the vector registers (twice as fast as
// compose_block_fast, docs/performance.md). Chosen at run time; the tests compare it with the
// scalar definition.
#define COUNTERSHADE_AVX512 __attribute__((target("avx2,bmi2,avx512f,avx512dq,avx512vl,avx512bw")))
// GCC 12 warns inside its own AVX-512 headers (their "undefined" source vectors).
#if !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

// The code values (code / levels) of eight linear values, clamped as clamp_unit4 does.
COUNTERSHADE_AVX512 inline __m256 quantize8(__m512d c, const CodeQuantizer::Table& table,
                                            __m512d inverse_levels) {
  const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0);
  c = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(c, zero, _CMP_LT_OQ), c,
                           zero);  // NaN stays, as there
  c = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(c, one, _CMP_GT_OQ), c, one);
  const __m512i bits = _mm512_castpd_si512(c);
  const __m512i raw = _mm512_sub_epi64(_mm512_sra_epi64(bits, _mm_cvtsi32_si128(table.shift)),
                                       _mm512_set1_epi64(table.offset));
  const __mmask8 inside = _mm512_cmpge_epi64_mask(raw, _mm512_setzero_si512());  // x ≥ 2^-30
  const __m512i bucket = _mm512_min_epi64(_mm512_max_epi64(raw, _mm512_setzero_si512()),
                                          _mm512_set1_epi64(table.last));
  const __m512i word =
      _mm512_i64gather_epi64(bucket, reinterpret_cast<const long long*>(table.packed), 8);
  const __m512i low = _mm512_set1_epi64(int64_t((uint64_t(1) << table.shift) - 1));
  const __mmask8 above =
      inside & _mm512_cmpge_epu64_mask(
                   _mm512_and_si512(bits, low),
                   _mm512_and_si512(word, _mm512_set1_epi64(int64_t(CodeQuantizer::kLowBits))));
  const __m512i below = _mm512_srli_epi64(word, 48);
  const __m512i code = _mm512_mask_add_epi64(below, above, below, _mm512_set1_epi64(1));
  return _mm512_cvtpd_ps(_mm512_mul_pd(_mm512_cvtepi64_pd(code), inverse_levels));
}

// The mask of the 24 floats of eight RGB pixels whose pixel's bit is set in `pixels`.
COUNTERSHADE_AVX512 inline uint32_t channel_mask(uint32_t pixels) {
  return _pdep_u32(pixels, 0x249249u) * 7u;  // bit 3i of pixel i, spread to bits 3i..3i+2
}

// Eight pixels' Lab and the lightness-only change: their linear RGB, and the target L*.
struct Rgb8 {
  RgbLanes<v8d> rgb;
  v8d target;
};
COUNTERSHADE_AVX512 inline Rgb8 lightness_to_rgb8(const Lab* lab, const double* delta) {
  v8d v0, v1, v2, d;
  const double* p = reinterpret_cast<const double*>(lab);  // 24 doubles: L a b L a b ...
  std::memcpy(&v0, p, sizeof v0);
  std::memcpy(&v1, p + 8, sizeof v1);
  std::memcpy(&v2, p + 16, sizeof v2);
  std::memcpy(&d, delta, sizeof d);
  const v8d L = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 0, 3, 6, 9, 12, 15, 0, 0),
                                        v2, 0, 1, 2, 3, 4, 5, 10, 13);
  const v8d a = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 1, 4, 7, 10, 13, 0, 0, 0),
                                        v2, 0, 1, 2, 3, 4, 8, 11, 14);
  const v8d b = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 2, 5, 8, 11, 14, 0, 0, 0),
                                        v2, 0, 1, 2, 3, 4, 9, 12, 15);
  const v8d target = L + d;
  return {lightness_to_rgb(L, a, b, target), target};
}

COUNTERSHADE_AVX512 inline __m512d as_m512d(v8d v) {
  __m512d out;
  std::memcpy(&out, &v, sizeof out);
  return out;
}

// Which of eight pixels clip, as Rgb4::clipped: the target L* outside [0, 100] or a channel outside
// [0, 1] beyond round-off.
COUNTERSHADE_AVX512 inline __mmask8 clip_mask8(const RgbLanes<v8d>& rgb, v8d target) {
  const __m512d t = as_m512d(target);
  __mmask8 clip = _mm512_cmp_pd_mask(t, _mm512_setzero_pd(), _CMP_LT_OQ) |
                  _mm512_cmp_pd_mask(t, _mm512_set1_pd(100.0), _CMP_GT_OQ);
  for (const v8d* c : {&rgb.r, &rgb.g, &rgb.b}) {
    const __m512d v = as_m512d(*c);
    clip |= _mm512_cmp_pd_mask(v, _mm512_set1_pd(-1e-9), _CMP_LT_OQ) |
            _mm512_cmp_pd_mask(v, _mm512_set1_pd(1.0 + 1e-9), _CMP_GT_OQ);
  }
  return clip;
}

// Writes eight pixels' codes interleaved as RGB, keeping the input's floats where `keep` (one bit
// per float) is set.
COUNTERSHADE_AVX512 inline void store_rgb8(__m256 r, __m256 g, __m256 b, const float* in,
                                           uint32_t keep, float* out) {
  const __m512 rg = _mm512_insertf32x8(_mm512_castps256_ps512(r), g, 1);
  const __m512 bb = _mm512_castps256_ps512(b);
  const __m512i first = _mm512_setr_epi32(0, 8, 16, 1, 9, 17, 2, 10, 18, 3, 11, 19, 4, 12, 20, 5);
  const __m256i last = _mm256_setr_epi32(13, 21, 6, 14, 22, 7, 15, 23);
  const __m512 head = _mm512_permutex2var_ps(rg, first, bb);
  const __m256 tail =
      _mm512_castps512_ps256(_mm512_permutex2var_ps(rg, _mm512_castsi256_si512(last), bb));
  // Masked loads read only the kept floats: with none kept (the usual case) the input's memory is
  // not read at all.
  _mm512_storeu_ps(out, _mm512_mask_loadu_ps(head, __mmask16(keep), in));
  _mm256_storeu_ps(out + 16, _mm256_mask_loadu_ps(tail, __mmask8(keep >> 16), in + 16));
}

COUNTERSHADE_AVX512 size_t compose_block_avx512(const Lab* lab, const float* in,
                                                const double* delta, size_t count,
                                                const CodeQuantizer::Table& table,
                                                double inverse_levels, float* out) {
  size_t clipped = 0;
  const __m512d inverse = _mm512_set1_pd(inverse_levels);
  for (size_t k = 0; k + 8 <= count; k += 8) {
    const __mmask8 unchanged =
        _mm512_cmp_pd_mask(_mm512_loadu_pd(delta + k), _mm512_setzero_pd(), _CMP_EQ_OQ);
    if (unchanged == 0xff) {
      std::copy(in + 3 * k, in + 3 * k + 24, out + 3 * k);  // background, λ = 0
      continue;
    }
    const Rgb8 pixels = lightness_to_rgb8(lab + k, delta + k);
    const RgbLanes<v8d>& rgb = pixels.rgb;
    store_rgb8(quantize8(as_m512d(rgb.r), table, inverse),
               quantize8(as_m512d(rgb.g), table, inverse),
               quantize8(as_m512d(rgb.b), table, inverse), in + 3 * k, channel_mask(unchanged),
               out + 3 * k);
    clipped += size_t(std::popcount(uint32_t(clip_mask8(rgb, pixels.target) & ~unchanged)));
  }
  return clipped;
}
#if !defined(__clang__)
#pragma GCC diagnostic pop
#endif

// The same for quantizers without a table (16-bit output): one exact lookup per channel.
size_t compose_block_slow(const Lab* lab, const float* in, const double* delta, size_t count,
                          const CodeQuantizer& quantizer, float* out) {
  size_t clipped = 0;
  for (size_t k = 0; k < count; ++k) {
    if (delta[k] == 0.0) {
      std::copy(in + 3 * k, in + 3 * k + 3, out + 3 * k);
      continue;
    }
    const double target = lab[k].L + delta[k];
    const glm::dvec3 c = lab_to_linear_rgb(with_lightness(lab[k], target));
    bool clip = target < 0.0 || target > 100.0;
    for (int ch = 0; ch < 3; ++ch) {
      clip |= c[ch] < -1e-9 || c[ch] > 1.0 + 1e-9;
      out[3 * k + ch] = quantizer.value(c[ch]);
    }
    clipped += clip;
  }
  return clipped;
}

// Lanes of L*, a* and b* stored as consecutive Lab pixels: two two-source shuffles per output
// vector (one permute each with AVX-512), rather than one extraction per value.
template <typename D>
[[gnu::always_inline]] inline void store_lab_lanes(const D& L, const D& a, const D& b, Lab* out) {
  D v[3];
  if constexpr (sizeof(D) == 64) {
    v[0] = __builtin_shufflevector(__builtin_shufflevector(L, a, 0, 8, 0, 1, 9, 0, 2, 10), b, 0, 1,
                                   8, 3, 4, 9, 6, 7);
    v[1] = __builtin_shufflevector(__builtin_shufflevector(L, a, 0, 3, 11, 0, 4, 12, 0, 5), b, 10,
                                   1, 2, 11, 4, 5, 12, 7);
    v[2] = __builtin_shufflevector(__builtin_shufflevector(L, a, 13, 0, 6, 14, 0, 7, 15, 0), b, 0,
                                   13, 2, 3, 14, 5, 6, 15);
  } else {
    v[0] = __builtin_shufflevector(__builtin_shufflevector(L, a, 0, 4, 0, 1), b, 0, 1, 4, 3);
    v[1] = __builtin_shufflevector(__builtin_shufflevector(L, a, 5, 0, 2, 6), b, 0, 5, 2, 3);
    v[2] = __builtin_shufflevector(__builtin_shufflevector(L, a, 0, 3, 7, 0), b, 6, 1, 2, 7);
  }
  static_assert(sizeof(Lab) == 3 * sizeof(double));
  double* o = reinterpret_cast<double*>(out);
  if (reinterpret_cast<uintptr_t>(o) % 16 != 0) return (void)std::memcpy(o, v, sizeof v);
  // Streaming stores (see parallel_blocks): the 50 MB of a view's CIELAB are not read back soon,
  // and they then skip reading every line before writing it.
  const double* d = reinterpret_cast<const double*>(v);
  constexpr size_t kDoubles = 3 * sizeof(D) / sizeof(double);  // the three vectors' doubles
  for (size_t i = 0; i < kDoubles; i += 2) _mm_stream_pd(o + i, _mm_loadu_pd(d + i));
}

// Lanes of R, G and B from three planes, from pixel k on.
template <typename D>
[[gnu::always_inline]] inline RgbLanes<D> load_rgb_lanes(const double* r, const double* g,
                                                         const double* b, size_t k) {
  RgbLanes<D> out;
  std::memcpy(&out.r, r + k, sizeof out.r);
  std::memcpy(&out.g, g + k, sizeof out.g);
  std::memcpy(&out.b, b + k, sizeof out.b);
  return out;
}

// linear_rgb_to_lab on the lanes of D at once (eight or four pixels), lane by lane the operations
// of the scalar code in core/color.
template <typename D, typename I>
[[gnu::always_inline]] inline void linear_to_lab_lanes(const double* r, const double* g,
                                                       const double* b, size_t count, Lab* out,
                                                       float* lightness) {
  using namespace color_constants;
  constexpr int N = sizeof(D) / sizeof(double);
  for (size_t k = 0; k + N <= count; k += N) {
    const RgbLanes<D> p = load_rgb_lanes<D>(r, g, b, k);
    const D &R = p.r, &G = p.g, &B = p.b;
    const D X = kRgbToXyz[0][0] * R + kRgbToXyz[0][1] * G + kRgbToXyz[0][2] * B;
    const D Y = kRgbToXyz[1][0] * R + kRgbToXyz[1][1] * G + kRgbToXyz[1][2] * B;
    const D Z = kRgbToXyz[2][0] * R + kRgbToXyz[2][1] * G + kRgbToXyz[2][2] * B;
    const D fx = lab_f_lanes<D, I>(X * kInverseWhite[0]),
            fy = lab_f_lanes<D, I>(Y * kInverseWhite[1]),
            fz = lab_f_lanes<D, I>(Z * kInverseWhite[2]);
    const D L = 116.0 * fy - 16.0, a = 500.0 * (fx - fy), bb = 200.0 * (fy - fz);
    store_lab_lanes(L, a, bb, out + k);
    if (lightness) {
      using Singles = std::conditional_t<sizeof(D) == 64, v8f, v4f>;
      const auto single = __builtin_convertvector(L, Singles);
      std::memcpy(lightness + k, &single, sizeof single);
    }
  }
  for (size_t k = count / N * N; k < count; ++k) {
    out[k] = linear_rgb_to_lab({r[k], g[k], b[k]});
    if (lightness) lightness[k] = float(out[k].L);
  }
}

COUNTERSHADE_AVX512_FUNCTION
void linear_to_lab_avx512(const double* r, const double* g, const double* b, size_t count, Lab* out,
                          float* lightness) {
  linear_to_lab_lanes<WideLanes, WideLaneBits>(r, g, b, count, out, lightness);
}

COUNTERSHADE_AVX2_CLONES
void linear_to_lab_avx2(const double* r, const double* g, const double* b, size_t count, Lab* out,
                        float* lightness) {
  linear_to_lab_lanes<NarrowLanes, NarrowLaneBits>(r, g, b, count, out, lightness);
}

// L* alone, by the operations that give linear_to_lab_lanes its L*: the same values, a third of
// the cube roots and none of the stores of a* and b*.
template <typename D, typename I>
[[gnu::always_inline]] inline void linear_to_lightness_lanes(const double* r, const double* g,
                                                             const double* b, size_t count,
                                                             double* lightness) {
  using namespace color_constants;
  constexpr int N = sizeof(D) / sizeof(double);
  for (size_t k = 0; k + N <= count; k += N) {
    const RgbLanes<D> p = load_rgb_lanes<D>(r, g, b, k);
    const D Y = kRgbToXyz[1][0] * p.r + kRgbToXyz[1][1] * p.g + kRgbToXyz[1][2] * p.b;
    const D L = 116.0 * lab_f_lanes<D, I>(Y * kInverseWhite[1]) - 16.0;
    std::memcpy(lightness + k, &L, sizeof L);
  }
  for (size_t k = count / N * N; k < count; ++k)
    lightness[k] = linear_rgb_to_lab({r[k], g[k], b[k]}).L;
}

COUNTERSHADE_AVX512_FUNCTION
void linear_to_lightness_avx512(const double* r, const double* g, const double* b, size_t count,
                                double* lightness) {
  linear_to_lightness_lanes<WideLanes, WideLaneBits>(r, g, b, count, lightness);
}

COUNTERSHADE_AVX2_CLONES
void linear_to_lightness_avx2(const double* r, const double* g, const double* b, size_t count,
                              double* lightness) {
  linear_to_lightness_lanes<NarrowLanes, NarrowLaneBits>(r, g, b, count, lightness);
}

// The code of a value (code / levels) and whether the value is exactly its code's value, for a
// float (I = int32_t) or lanes of floats (I: lanes of int32_t).
template <typename F, typename I>
[[gnu::always_inline]] inline I code_of(F v, float levels, I* exact) {
  const F unit = v >= 0.0f ? (v <= 1.0f ? v : 1.0f) : 0.0f;  // NaN: 0, not exact below
  const I code = convert_lanes<I>(unit * levels + 0.5f);
  *exact &= convert_lanes<F>(code) / levels == v;
  return code;
}

}  // namespace

void linear_to_lab_block(const double* r, const double* g, const double* b, size_t count, Lab* out,
                         float* lightness) {
  (has_avx512() ? linear_to_lab_avx512 : linear_to_lab_avx2)(r, g, b, count, out, lightness);
}

void linear_to_lightness_block(const double* r, const double* g, const double* b, size_t count,
                               double* lightness) {
  (has_avx512() ? linear_to_lightness_avx512 : linear_to_lightness_avx2)(r, g, b, count, lightness);
}

// The codes of n values (code / levels), and whether every value is exactly its code's value.
// Eight lanes at a time in vectors: written as a plain loop, the comparisons (which may trap on
// NaN) kept GCC from vectorising it for processors without AVX-512 (6 times slower).
COUNTERSHADE_CLONES
bool exact_codes(const float* values, size_t n, float levels, int32_t* code) {
  v8i exact8 = v8i{} - 1;
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    v8f v;
    std::memcpy(&v, values + i, sizeof v);
    const v8i c = code_of(v, levels, &exact8);
    std::memcpy(code + i, &c, sizeof c);
  }
  int32_t exact = 1;
  for (int lane = 0; lane < 8; ++lane) exact &= exact8[lane] != 0;
  for (; i < n; ++i) code[i] = code_of(values[i], levels, &exact);
  return exact;
}

// The table's values of the codes of `count` RGB pixels (code[3k + channel]), one plane per
// channel. Scalar loads: AVX-512 gathers of the same loop measured slower (11 % of the conversion
// against 19 %).
void gather_planes(const int32_t* __restrict code, size_t count, const double* __restrict table,
                   double* __restrict r, double* __restrict g, double* __restrict b) {
  for (size_t k = 0; k < count; ++k) {
    r[k] = table[code[3 * k]];
    g[k] = table[code[3 * k + 1]];
    b[k] = table[code[3 * k + 2]];
  }
}

LightnessComposer::LightnessComposer(const CodeQuantizer& quantizer, int bits)
    : quantizer_(quantizer),
      table_(quantizer.uses_table() ? std::optional(quantizer.table()) : std::nullopt),
      inverse_levels_(1.0 / double(float((1u << bits) - 1u))),  // see code_fraction
      eight_(has_avx512()) {}

size_t LightnessComposer::compose(const Lab* lab, const float* source, const double* delta,
                                  size_t count, float* target) const {
  size_t clipped = 0, done = 0;
  if (table_ &&
      eight_) {  // never called elsewhere: its code needs AVX-512 from its first instruction
    done = count / 8 * 8;
    clipped += compose_block_avx512(lab, source, delta, done, *table_, inverse_levels_, target);
  }
  if (table_) {
    const size_t four = (count - done) / 4 * 4;
    clipped += compose_block_fast(lab + done, source + 3 * done, delta + done, four, *table_,
                                  inverse_levels_, target + 3 * done);
    done += four;
  }
  return clipped + compose_block_slow(lab + done, source + 3 * done, delta + done, count - done,
                                      quantizer_, target + 3 * done);
}

}  // namespace countershade
