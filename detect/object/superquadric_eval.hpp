#pragma once
// SuperquadricMetric::evaluate: G = F^eps1 and its gradient, written once for a double and for
// four lanes (detect/lanes.hpp). Included by superquadric.cpp (the scalar metric) and by
// pose_fit.cpp (its vectorised linearisation); every function is forced inline so that a caller
// compiled for AVX2 gets AVX2 code.

#include "detect/common/lanes.hpp"
#include "detect/object/superquadric.hpp"

namespace rangefit {

namespace superquadric_detail {
// Tapering factors are clamped here: beyond the tip of a cone the part does not exist.
constexpr double kMinTaperFactor = 1e-9;
// Normalised coordinates below this (relative to the largest one) count as zero for gradients.
constexpr double kTinyRatio = 1e-12;
// G saturates here instead of overflowing (finite points farther than ~1e150 part sizes).
constexpr double kMaxScale = 1e150;
}  // namespace superquadric_detail

template <class V>
[[gnu::always_inline]] inline V SuperquadricMetric::Power::operator()(V x) const {
  // The exponents of the usual shapes (eps 0.1, 0.5, 1, 2) multiplied out without a loop;
  // x^e as exp(e log x) for the rest (x >= 0 here).
  switch (n) {
    case -1:
      return lanes::pow_positive(x, e);
    case 1:
      return x;
    case 2:
      return x * x;
    case 10: {
      const V x2 = x * x, x4 = x2 * x2;
      return x4 * x4 * x2;
    }
    case 20: {
      const V x2 = x * x, x4 = x2 * x2, x10 = x4 * x4 * x2;
      return x10 * x10;
    }
    default: {
      V r = lanes::splat<V>(1.0);
      for (int k = n; k > 0; k >>= 1) {
        if (k & 1) r *= x;
        x *= x;
      }
      return r;
    }
  }
}

template <class V, bool kGradient>
[[gnu::always_inline]] inline V SuperquadricMetric::evaluate(V x, V y, V z, V* gx_out, V* gy_out,
                                                             V* gz_out) const {
  using namespace superquadric_detail;
  using lanes::splat;
  // Undo eq. 2.19-2.21: X = fx(z) x, Y = fy(z) y, Z = z (skipped for untapered parts).
  V fx_raw = splat<V>(1.0), fy_raw = fx_raw, fx = fx_raw, fy = fx_raw;
  if (tapered_) {
    fx_raw = 1.0 + sq_.kx / sq_.a3 * z;
    fy_raw = 1.0 + sq_.ky / sq_.a3 * z;
    fx = lanes::max(fx_raw, splat<V>(kMinTaperFactor));
    fy = lanes::max(fy_raw, splat<V>(kMinTaperFactor));
    x = x / fx;
    y = y / fy;
  }
  const V nx = lanes::abs(x) * inv_a1_, ny = lanes::abs(y) * inv_a2_, nz = lanes::abs(z) * inv_a3_;
  const V s = lanes::max(lanes::max(nx, ny), nz);
  // G is 0 at the centre (and for NaN input, which gives 0 rather than NaN) and saturates far
  // away (also for infinity); other lanes are computed with s = 1 and selected away.
  const auto regular = (s > 0.0) & (s <= kMaxScale);
  const V special = s > 0.0 ? splat<V>(kMaxScale * kMaxScale) : splat<V>(0.0);
  const V sr = regular ? s : splat<V>(1.0);
  // Eq. 2.15 on the scaled point: every term is in [0, 1], F' in [1, 1 + 2^(eps2/eps1)].
  const V inv_s = 1.0 / sr;
  const V sx = nx * inv_s, sy = ny * inv_s, sz = nz * inv_s;
  const V ax = p_xy_(sx), ay = p_xy_(sy);
  const V a = ax + ay;
  const V u = p_a_(a);  // 0 for a = 0: every exponent is positive
  const V v = p_z_(sz);
  const V f = u + v;
  const V g = sr * sr * p_g_(f);  // eq. 5.1: G = F^eps1 = s^2 F'^eps1
  if constexpr (kGradient) {
    // dG/dx = 2 G (u/F)(ax/A) / x and dG/dz = 2 G (v/F) / z (x, z unscaled; |x| = sx s a1).
    const V zero = splat<V>(0.0);
    const V two_g_f = 2.0 * g / f;
    const V gu = a > 0.0 ? two_g_f * u / a : zero;
    const V gx = sx > kTinyRatio ? gu * ax / x : zero;
    const V gy = sy > kTinyRatio ? gu * ay / y : zero;
    const V gz = sz > kTinyRatio ? two_g_f * v / z : zero;
    V dx = gx, dy = gy, dz = gz;
    if (tapered_) {
      // Chain rule through the inverse taper: x = X / fx(Z), dx/dZ = -x kx / (a3 fx).
      const V dx_dz = fx_raw < kMinTaperFactor ? zero : -x * sq_.kx / (sq_.a3 * fx);
      const V dy_dz = fy_raw < kMinTaperFactor ? zero : -y * sq_.ky / (sq_.a3 * fy);
      dx = gx / fx;
      dy = gy / fy;
      dz = gz + gx * dx_dz + gy * dy_dz;
    }
    // Finite everywhere: zero where the value is special or a component is not finite.
    constexpr double kMax = 0x1.fffffffffffffp1023;
    const auto keep =
        regular & (lanes::abs(dx) <= kMax) & (lanes::abs(dy) <= kMax) & (lanes::abs(dz) <= kMax);
    *gx_out = keep ? dx : zero;
    *gy_out = keep ? dy : zero;
    *gz_out = keep ? dz : zero;
  }
  return regular ? g : special;
}

}  // namespace rangefit
