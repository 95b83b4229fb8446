#pragma once
// 3-vectors whose coordinates are lanes (core/lane_math.h): one direction per lane, with the few
// operations the vectorised shading hooks need. D is double or a GCC vector of doubles.

#include <cstddef>
#include <cstring>

namespace countershade {

template <typename D>
struct Vec3Lanes {
  D x, y, z;
};

template <typename D>
[[gnu::always_inline]] inline Vec3Lanes<D> operator+(const Vec3Lanes<D>& a, const Vec3Lanes<D>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename D>
[[gnu::always_inline]] inline Vec3Lanes<D> operator-(const Vec3Lanes<D>& a, const Vec3Lanes<D>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename D>
[[gnu::always_inline]] inline Vec3Lanes<D> operator*(const Vec3Lanes<D>& a, const D& s) {
  return {a.x * s, a.y * s, a.z * s};
}
template <typename D>
[[gnu::always_inline]] inline Vec3Lanes<D> operator/(const Vec3Lanes<D>& a, const D& s) {
  return {a.x / s, a.y / s, a.z / s};
}
template <typename D>
[[gnu::always_inline]] inline D dot(const Vec3Lanes<D>& a, const Vec3Lanes<D>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename D>
[[gnu::always_inline]] inline Vec3Lanes<D> cross(const Vec3Lanes<D>& a, const Vec3Lanes<D>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Per lane: a where the mask is set, else b.
template <typename D, typename M>
[[gnu::always_inline]] inline Vec3Lanes<D> select_lanes(const M& mask, const Vec3Lanes<D>& a,
                                                        const Vec3Lanes<D>& b) {
  return {mask ? a.x : b.x, mask ? a.y : b.y, mask ? a.z : b.z};
}

// The vectors at [first, first + lanes) of three coordinate planes, and back.
template <typename D, size_t N>
[[gnu::always_inline]] inline Vec3Lanes<D> load_lanes(const double (&planes)[3][N], size_t first) {
  Vec3Lanes<D> v;
  std::memcpy(&v.x, planes[0] + first, sizeof v.x);
  std::memcpy(&v.y, planes[1] + first, sizeof v.y);
  std::memcpy(&v.z, planes[2] + first, sizeof v.z);
  return v;
}
template <typename D, size_t N>
[[gnu::always_inline]] inline void store_lanes(const Vec3Lanes<D>& v, double (&planes)[3][N],
                                               size_t first) {
  std::memcpy(planes[0] + first, &v.x, sizeof v.x);
  std::memcpy(planes[1] + first, &v.y, sizeof v.y);
  std::memcpy(planes[2] + first, &v.z, sizeof v.z);
}

}  // namespace countershade
