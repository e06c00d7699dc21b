#pragma once
// Arithmetic written once for a double and for four doubles in a GCC/Clang vector (V4d), so a
// vectorised kernel and its scalar twin give the same results bit for bit. Comparisons give bool
// on a double and a lane mask on a V4d; `c ? a : b` selects per lane on both.
//
// pow_positive() is x^e as exp(e log x) with polynomial log and exp instead of libm: glibc's exp
// and log were a third of a pose fit's time (perf, 50 points) and do not vectorise without
// -ffast-math. Their relative error is below 1e-15 (tested against std::pow).

#include <bit>
#include <cmath>
#include <cstdint>
#if defined(__x86_64__)
#include <emmintrin.h>
#endif

namespace rangefit::lanes {

// Kernels written with these types are compiled twice, for SSE2 and with
// [[gnu::target("avx2")]] (not FMA: fused products would round differently), and pick their
// AVX2 copy at run time when the CPU has it.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define RANGEFIT_LANES_AVX2 1
inline bool cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#else
inline bool cpu_has_avx2() { return false; }
#endif

using V4d = double __attribute__((vector_size(32)));
using V4i = std::int64_t __attribute__((vector_size(32)));

[[gnu::always_inline]] inline std::int64_t bits(double x) { return std::bit_cast<std::int64_t>(x); }
[[gnu::always_inline]] inline double from_bits(std::int64_t b) { return std::bit_cast<double>(b); }
[[gnu::always_inline]] inline V4i bits(V4d x) { return reinterpret_cast<V4i>(x); }
[[gnu::always_inline]] inline V4d from_bits(V4i b) { return reinterpret_cast<V4d>(b); }

// A constant as V (broadcast on a vector).
template <class V>
[[gnu::always_inline]] inline V splat(double c) {
  return V{} + c;
}

template <class V>
[[gnu::always_inline]] inline V abs(V x) {
  return from_bits(bits(x) & 0x7fffffffffffffff);
}

// std::max's semantics, lane by lane (a NaN in a is kept).
template <class V>
[[gnu::always_inline]] inline V max(V a, V b) {
  return a < b ? b : a;
}

// Square root, lane by lane, correctly rounded as std::sqrt (no errno, so it vectorises: two SSE2
// square roots per V4d on x86-64).
[[gnu::always_inline]] inline double sqrt(double x) { return std::sqrt(x); }
[[gnu::always_inline]] inline V4d sqrt(V4d x) {
#if defined(__x86_64__)
  const __m128d lo = _mm_sqrt_pd(__m128d{x[0], x[1]}), hi = _mm_sqrt_pd(__m128d{x[2], x[3]});
  return V4d{lo[0], lo[1], hi[0], hi[1]};
#else
  return V4d{std::sqrt(x[0]), std::sqrt(x[1]), std::sqrt(x[2]), std::sqrt(x[3])};
#endif
}

// Small integers (|k| < 2^51) stored as int64 to double without a conversion instruction (AVX2
// has none for 64-bit integers): the integer is added to the mantissa of 1.5 * 2^52.
template <class V, class I>
[[gnu::always_inline]] inline V small_int_to_double(I k) {
  constexpr double kMagic = 0x1.8p52;
  return from_bits(k + bits(kMagic)) - kMagic;
}

// Natural log of x > 0 in the normal range (not checked: the caller selects other lanes away).
// x = z 2^k with z in [sqrt(1/2), sqrt(2)), log z = 2 atanh(t) with t = (z - 1)/(z + 1), |t| <=
// 0.1716, as an odd series to t^17 (next term < 3e-16).
template <class V>
[[gnu::always_inline]] inline V log_positive(V x) {
  constexpr std::int64_t kSqrtHalfBits = 0x3fe6a09e667f3bcd;
  constexpr double kLn2Hi = 0x1.62e42fefa3800p-1, kLn2Lo = 0x1.ef35793c76730p-45;
  const auto b = bits(x);
  const auto k = (b - kSqrtHalfBits) >> 52;  // arithmetic shift: floor(log2(x / sqrt(1/2)))
  const V z = from_bits(b - (k << 52));
  const V t = (z - 1.0) / (z + 1.0);
  const V t2 = t * t;
  // 1/3 + t2/5 + ... + t2^7/17 by Estrin's scheme: short dependency chains, so the lanes of
  // neighbouring points overlap (Horner's chain dominated the pose fit's time).
  const V t4 = t2 * t2, t8 = t4 * t4;
  const V p01 = 1.0 / 3.0 + t2 * (1.0 / 5.0), p23 = 1.0 / 7.0 + t2 * (1.0 / 9.0);
  const V p45 = 1.0 / 11.0 + t2 * (1.0 / 13.0), p67 = 1.0 / 15.0 + t2 * (1.0 / 17.0);
  const V p = (p01 + t4 * p23) + t8 * (p45 + t4 * p67);
  const V log_z = 2.0 * t + 2.0 * t * t2 * p;
  const V kd = small_int_to_double<V>(k);
  return kd * kLn2Hi + (log_z + kd * kLn2Lo);
}

// e^y for y in [-708, 709] (clamped to it; NaN gives e^-708): y = k ln2 + r, |r| <= ln2 / 2,
// e^r by its Taylor series, 2^k put into the exponent bits.
template <class V>
[[gnu::always_inline]] inline V exp_clamped(V y) {
  constexpr double kLog2e = 0x1.71547652b82fep0;
  constexpr double kLn2Hi = 0x1.62e42fefa3800p-1, kLn2Lo = 0x1.ef35793c76730p-45;
  constexpr double kRound = 0x1.8p52;
  y = y > -708.0 ? y : splat<V>(-708.0);
  y = y < 709.0 ? y : splat<V>(709.0);
  const V shifted = y * kLog2e + kRound;  // round to nearest in the last mantissa bit
  const V kd = shifted - kRound;
  const auto k = bits(shifted) - bits(kRound);
  const V r = (y - kd * kLn2Hi) - kd * kLn2Lo;
  // Taylor coefficients 1/i! to i = 12 (next term < 2e-16), summed by Estrin's scheme.
  const V r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
  const V q01 = 1.0 + r, q23 = 0.5 + r * (1.0 / 6.0), q45 = 1.0 / 24.0 + r * (1.0 / 120.0);
  const V q67 = 1.0 / 720.0 + r * (1.0 / 5040.0), q89 = 1.0 / 40320.0 + r * (1.0 / 362880.0);
  const V q1011 = 1.0 / 3628800.0 + r * (1.0 / 39916800.0);
  const V q12 = splat<V>(1.0 / 479001600.0);
  const V p = ((q01 + r2 * q23) + r4 * (q45 + r2 * q67)) + r8 * ((q89 + r2 * q1011) + r4 * q12);
  return p * from_bits((k + 1023) << 52);
}

// x^e for e > 0: exp(e log x) for normal x > 0, 0 for smaller x (and for NaN).
template <class V>
[[gnu::always_inline]] inline V pow_positive(V x, double e) {
  constexpr double kMinNormal = 0x1p-1022;
  return x >= kMinNormal ? exp_clamped<V>(e * log_positive<V>(x)) : splat<V>(0.0);
}

}  // namespace rangefit::lanes
