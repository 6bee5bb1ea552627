/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Per-point loops on four-lane vectors (see laser_kernels.h).
#include "laser_kernels.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace vpLaserSolvers
{
namespace detail
{
namespace
{
#if defined(__GNUC__)
typedef double Lanes __attribute__((vector_size(4 * sizeof(double))));
typedef std::int64_t LaneMask __attribute__((vector_size(4 * sizeof(double))));
typedef int Quad __attribute__((vector_size(4 * sizeof(int))));
#endif

constexpr int kLanes = 4;

VSP_LASER_INLINE double sqrtOf(double v) { return std::sqrt(v); }
#if defined(__GNUC__)
VSP_LASER_INLINE Lanes sqrtOf(const Lanes &v)
{
  return Lanes{std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3])};
}
#endif
} // namespace

VSP_LASER_KERNEL int scoreConicChunk(const ConicCoefficients &c, const double *x, const double *y, int first, int size,
                                     double thr2, double &cost, int *inliers)
{
  const double thr2Times4 = 4.0 * thr2;
  int count = 0;
  double sum = 0.0;
  int j = 0;
#if defined(__GNUC__)
  // A point is an inlier when (x^T c x)^2 < thr2 |grad|^2 (no division; NaN compares false); its
  // truncated cost is the squared distance then, thr2 otherwise. The index of every point is written
  // at the end of the list, which only advances for an inlier: no branch per point.
  Lanes acc = {0.0, 0.0, 0.0, 0.0};
  const Lanes t4 = {thr2Times4, thr2Times4, thr2Times4, thr2Times4}, t = {thr2, thr2, thr2, thr2};
  for (; j + kLanes <= size; j += kLanes) {
    Lanes X, Y;
    std::memcpy(&X, x + j, sizeof X);
    std::memcpy(&Y, y + j, sizeof Y);
    const Lanes v0 = c.a * X + c.b * Y + c.d, v1 = c.b * X + c.e * Y + c.f;
    const Lanes algebraic = X * v0 + Y * v1 + (c.d * X + c.f * Y + c.g);
    const Lanes a2 = algebraic * algebraic, g2 = v0 * v0 + v1 * v1;
    const LaneMask in = a2 < t4 * g2;
    const Lanes d2 = a2 / (4.0 * g2);
    acc += in ? d2 : t;
    for (int l = 0; l < kLanes; ++l) {
      inliers[count] = first + j + l;
      count -= static_cast<int>(in[l]); // -1 for an inlier
    }
  }
  sum = (acc[0] + acc[1]) + (acc[2] + acc[3]);
#endif
  for (; j < size; ++j) {
    double v0, v1;
    const double algebraic = c.apply(x[j], y[j], v0, v1);
    const double a2 = algebraic * algebraic, g2 = v0 * v0 + v1 * v1;
    const bool in = a2 < thr2Times4 * g2;
    sum += in ? a2 / (4.0 * g2) : thr2;
    inliers[count] = first + j;
    count += in ? 1 : 0;
  }
  cost += sum;
  return count;
}

namespace
{
#if defined(__GNUC__)
//! Lane sums of the normal equations, reduced to PlaneTermsSums at the end.
struct LaneSums
{
  Lanes h[6], g[3], cost;
};

VSP_LASER_INLINE Lanes broadcast(double v) { return Lanes{v, v, v, v}; }

VSP_LASER_INLINE double laneTotal(const Lanes &v) { return (v[0] + v[1]) + (v[2] + v[3]); }

//! The coordinates of the four points from \e p, one point per lane.
VSP_LASER_INLINE void loadFour(const Eigen::Vector2d *p, Lanes &x, Lanes &y)
{
  x = Lanes{p[0](0), p[1](0), p[2](0), p[3](0)};
  y = Lanes{p[0](1), p[1](1), p[2](1), p[3](1)};
}

VSP_LASER_INLINE void reduce(const LaneSums &s, PlaneTermsSums &out)
{
  for (int i = 0; i < 6; ++i)
    out.h[i] += laneTotal(s.h[i]);
  for (int i = 0; i < 3; ++i)
    out.g[i] += laneTotal(s.g[i]);
  out.cost += laneTotal(s.cost);
}

VSP_LASER_INLINE void clear(LaneSums &s)
{
  const Lanes z = broadcast(0.0);
  for (Lanes &v : s.h)
    v = z;
  for (Lanes &v : s.g)
    v = z;
  s.cost = z;
}
#endif

//! Adds the weighted terms of one point (T = double, Sums = PlaneTermsSums) or of four (Lanes, LaneSums).
template <class Sums, class T>
VSP_LASER_INLINE void addTerms(Sums &s, const T &w, const T &r, const T &J0, const T &J1, const T &J2)
{
  const T wJ0 = w * J0, wJ1 = w * J1, wJ2 = w * J2;
  s.cost += w * r * r;
  s.h[0] += wJ0 * J0;
  s.h[1] += wJ0 * J1;
  s.h[2] += wJ0 * J2;
  s.h[3] += wJ1 * J1;
  s.h[4] += wJ1 * J2;
  s.h[5] += wJ2 * J2;
  s.g[0] += wJ0 * r;
  s.g[1] += wJ1 * r;
  s.g[2] += wJ2 * r;
}

/*!
  The terms of one point (the scalar form of the lanes below): the signed Sampson distance is
  r = A / (2 sqrt(B)) with A = x^T c x and B = |(c x)_{1,2}|^2, so dr = (dA - A dB / (2 B)) / (2 sqrt(B))
  with dA = x^T dc x and dB = 2 (c x)_{1,2} . (dc x)_{1,2}. Along a tangent, dc = t w^T + w t^T, so
  x^T dc x = 2 (t.x)(w.x) and (dc x)_{1,2} = t_{1,2} (w.x) + w_{1,2} (t.x): a few products per point.
  \return r; \e B is 0 where the conic has no gradient (r and the derivatives are then meaningless).
*/
template <class T>
VSP_LASER_INLINE T pointTerms(const PlaneTermsCoefficients &k, const T &x, const T &y, T &J0, T &J1, T &J2, T &B)
{
  const ConicCoefficients &c = k.c, &dd = k.dd;
  const T v0 = c.a * x + c.b * y + c.d, v1 = c.b * x + c.e * y + c.f;
  const T A = x * v0 + y * v1 + (c.d * x + c.f * y + c.g);
  B = v0 * v0 + v1 * v1;
  const T invB = 1.0 / B;
  const T invRoot = 0.5 * sqrtOf(invB), ratio = A * invB;
  const T wx = k.w[0] * x + k.w[1] * y + k.w[2], vw = v0 * k.w[0] + v1 * k.w[1];
  const T tx0 = k.t0[0] * x + k.t0[1] * y + k.t0[2], vt0 = v0 * k.t0[0] + v1 * k.t0[1];
  const T tx1 = k.t1[0] * x + k.t1[1] * y + k.t1[2], vt1 = v0 * k.t1[0] + v1 * k.t1[1];
  const T u0 = dd.a * x + dd.b * y + dd.d, u1 = dd.b * x + dd.e * y + dd.f;
  const T dA2 = x * u0 + y * u1 + (dd.d * x + dd.f * y + dd.g);
  J0 = (2.0 * tx0 * wx - ratio * (vt0 * wx + vw * tx0)) * invRoot;
  J1 = (2.0 * tx1 * wx - ratio * (vt1 * wx + vw * tx1)) * invRoot;
  J2 = (dA2 - ratio * (v0 * u0 + v1 * u1)) * invRoot;
  return A * invRoot;
}
} // namespace

VSP_LASER_KERNEL void planeTermsKernel(const PlaneTermsCoefficients &k, const Eigen::Vector2d *points,
                                       const double *weights, int n, double *r, double *j0, double *j1, double *j2,
                                       PlaneTermsSums &sums)
{
  sums = PlaneTermsSums();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  int i = 0;
#if defined(__GNUC__)
  LaneSums s;
  clear(s);
  const Lanes zero = broadcast(0.0), one = broadcast(1.0), nanLanes = broadcast(nan);
  for (; i + kLanes <= n; i += kLanes) {
    Lanes x, y;
    loadFour(points + i, x, y);
    Lanes w = one;
    if (weights)
      std::memcpy(&w, weights + i, sizeof w);
    Lanes J0, J1, J2, B;
    Lanes res = pointTerms(k, x, y, J0, J1, J2, B);
    const LaneMask valid = B > zero; // no gradient: NaN residual, zero derivatives, no contribution
    J0 = valid ? J0 : zero;
    J1 = valid ? J1 : zero;
    J2 = valid ? J2 : zero;
    w = valid ? w : zero;
    const Lanes stored = valid ? res : nanLanes;
    std::memcpy(r + i, &stored, sizeof stored);
    std::memcpy(j0 + i, &J0, sizeof J0);
    std::memcpy(j1 + i, &J1, sizeof J1);
    std::memcpy(j2 + i, &J2, sizeof J2);
    res = valid ? res : zero;
    addTerms(s, w, res, J0, J1, J2);
  }
  reduce(s, sums);
#endif
  for (; i < n; ++i) {
    double J0, J1, J2, B;
    const double res = pointTerms(k, points[i](0), points[i](1), J0, J1, J2, B);
    if (!(B > 0.0)) {
      r[i] = nan;
      j0[i] = j1[i] = j2[i] = 0.0;
      continue;
    }
    r[i] = res;
    j0[i] = J0;
    j1[i] = J1;
    j2[i] = J2;
    addTerms(sums, weights ? weights[i] : 1.0, res, J0, J1, J2);
  }
}

VSP_LASER_KERNEL void planeTermsSums(const double *r, const double *j0, const double *j1, const double *j2,
                                     const double *weights, int n, PlaneTermsSums &sums)
{
  sums = PlaneTermsSums();
  int i = 0;
#if defined(__GNUC__)
  LaneSums s;
  clear(s);
  const Lanes zero = broadcast(0.0);
  for (; i + kLanes <= n; i += kLanes) {
    Lanes w, res, J0, J1, J2;
    std::memcpy(&w, weights + i, sizeof w);
    std::memcpy(&res, r + i, sizeof res);
    std::memcpy(&J0, j0 + i, sizeof J0);
    std::memcpy(&J1, j1 + i, sizeof J1);
    std::memcpy(&J2, j2 + i, sizeof J2);
    res = w != zero ? res : zero; // a NaN residual has a zero weight
    addTerms(s, w, res, J0, J1, J2);
  }
  reduce(s, sums);
#endif
  for (; i < n; ++i) {
    if (weights[i] != 0.0) // a NaN residual has a zero weight
      addTerms(sums, weights[i], r[i], j0[i], j1[i], j2[i]);
  }
}

namespace
{
//! Sign bit as a 0/1 factor (scalar) or a lane mask.
VSP_LASER_INLINE double signFactor(double v) { return static_cast<double>(std::signbit(v)); }
VSP_LASER_INLINE double select(bool c, double a, double b) { return c ? a : b; }
VSP_LASER_INLINE double absOf(double v) { return std::abs(v); }
#if defined(__GNUC__)
VSP_LASER_INLINE LaneMask signFactor(const Lanes &v)
{
  LaneMask bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits < 0; // the sign bit is the integer sign
}
VSP_LASER_INLINE Lanes select(const LaneMask &c, const Lanes &a, const Lanes &b) { return c ? a : b; }
VSP_LASER_INLINE Lanes absOf(const Lanes &v) { return v < 0.0 ? -v : v; }
#endif

/*!
  The polynomial atan2 without branches (the points come in any order around the ellipse): the
  octant enters through selected increments and the sign of y through a sign flip, in the same
  operations for one value or four lanes.
*/
template <class T> VSP_LASER_INLINE T atan2Polynomial(const T &y, const T &x)
{
  const T ax = absOf(x), ay = absOf(y);
  const auto above = ay > ax;
  const T z = select(above, ax, ay) / select(above, ay, ax), z2 = z * z;
  T a = z2 * 0.0028662257 - 0.0161657367;
  for (double k : {0.0429096138, -0.0752896400, 0.1065626393, -0.1420889944, 0.1999355085, -0.3333314528, 1.0})
    a = a * z2 + k;
  a = a * z;
  const T zero = T();
  a = a + select(above, 0.5 * M_PI - 2.0 * a, zero);   // above the diagonal: pi / 2 - a
  a = a + select(signFactor(x), M_PI - 2.0 * a, zero); // left half-plane: pi - a
  return select(signFactor(y), -a, a);
}

//! The bin of the angle \e approximate (atan2Polynomial()), or of std::atan2 near a bin edge or for invalid input;
//! -1 when u has no angle (a NaN coordinate), whose conversion to an int would be undefined.
VSP_LASER_INLINE int binOf(double u0, double u1, double approximate, int bins)
{
  const double perRadian = bins / (2.0 * M_PI);
  if (std::isfinite(u0) && std::isfinite(u1) && (u0 != 0.0 || u1 != 0.0)) {
    const double t = (approximate + M_PI) * perRadian, f = std::floor(t);
    const double margin = 1e-6 * perRadian;
    if (t - f > margin && f + 1.0 - t > margin)
      return static_cast<int>(f);
  }
  const double angle = std::atan2(u1, u0);
  return std::isnan(angle) ? -1 : static_cast<int>(std::floor((angle + M_PI) * perRadian));
}
} // namespace

VSP_LASER_KERNEL void huberWeights(const double *r, int n, double k, double *w)
{
  const double inf = std::numeric_limits<double>::infinity();
  int i = 0;
#if defined(__GNUC__)
  const Lanes one = broadcast(1.0), infLanes = broadcast(inf);
  for (; i + kLanes <= n; i += kLanes) {
    Lanes a;
    std::memcpy(&a, r + i, sizeof a);
    a = absOf(a);
    const Lanes q = k / a;                                             // k / 0 = inf: weight 1
    const Lanes weight = a < infLanes ? (q < one ? q : one) : Lanes{}; // NaN compares false: weight 0
    std::memcpy(w + i, &weight, sizeof weight);
  }
#endif
  for (; i < n; ++i) {
    const double a = std::abs(r[i]);
    w[i] = a < inf ? std::min(1.0, k / a) : 0.0;
  }
}

VSP_LASER_KERNEL void centroidAndSpread(const Eigen::Vector2d *points, int n, double &cx, double &cy,
                                        double &meanDistance)
{
  double sx = 0.0, sy = 0.0;
  int i = 0;
#if defined(__GNUC__)
  Lanes ax = {}, ay = {};
  for (; i + kLanes <= n; i += kLanes) {
    Lanes x, y;
    loadFour(points + i, x, y);
    ax += x;
    ay += y;
  }
  sx = laneTotal(ax);
  sy = laneTotal(ay);
#endif
  for (; i < n; ++i) {
    sx += points[i](0);
    sy += points[i](1);
  }
  cx = sx / n;
  cy = sy / n;
  double sd = 0.0;
  i = 0;
#if defined(__GNUC__)
  Lanes ad = {};
  for (; i + kLanes <= n; i += kLanes) {
    Lanes x, y;
    loadFour(points + i, x, y);
    const Lanes dx = x - cx, dy = y - cy;
    ad += sqrtOf(dx * dx + dy * dy);
  }
  sd = laneTotal(ad);
#endif
  for (; i < n; ++i) {
    const double dx = points[i](0) - cx, dy = points[i](1) - cy;
    sd += std::sqrt(dx * dx + dy * dy);
  }
  meanDistance = sd / n;
}

VSP_LASER_KERNEL void ellipseBins(const Eigen::Vector2d *points, const int *indices, int n,
                                  const Eigen::Vector2d &centre, const Eigen::Matrix2d &U, int bins, int *out)
{
  const double c0 = centre(0), c1 = centre(1), u00 = U(0, 0), u01 = U(0, 1), u11 = U(1, 1);
  int i = 0;
#if defined(__GNUC__)
  const double perRadian = bins / (2.0 * M_PI), margin = 1e-6 * perRadian;
  const Lanes inf = broadcast(std::numeric_limits<double>::infinity());
  for (; i + kLanes <= n; i += kLanes) {
    Lanes px, py;
    for (int l = 0; l < kLanes; ++l) {
      px[l] = points[indices[i + l]](0);
      py[l] = points[indices[i + l]](1);
    }
    const Lanes dx = px - c0, dy = py - c1;
    const Lanes v0 = u00 * dx + u01 * dy, v1 = u11 * dy;
    const Lanes a = atan2Polynomial(v1, v0), t = (a + M_PI) * perRadian;
    // t >= 0 for a valid angle, where truncation is the floor (out-of-range lanes, NaN included, are
    // truncated from 0 instead); a lane is settled when its input is finite and not zero and its angle
    // is not within the margin of a bin edge.
    const Lanes inRange = ((t >= 0.0) & (t < bins + 1.0)) ? t : Lanes{};
    const Quad whole = __builtin_convertvector(inRange, Quad);
    const Lanes f = __builtin_convertvector(whole, Lanes);
    const LaneMask settled = (absOf(v0) < inf) & (absOf(v1) < inf) & ((v0 != 0.0) | (v1 != 0.0)) & (t - f > margin) &
                             (f + 1.0 - t > margin);
    std::memcpy(out + i, &whole, sizeof whole);
    if (!(settled[0] & settled[1] & settled[2] & settled[3]))
      for (int l = 0; l < kLanes; ++l)
        out[i + l] = binOf(v0[l], v1[l], a[l], bins);
  }
#endif
  for (; i < n; ++i) {
    const double dx = points[indices[i]](0) - c0, dy = points[indices[i]](1) - c1;
    const double v0 = u00 * dx + u01 * dy, v1 = u11 * dy;
    out[i] = binOf(v0, v1, atan2Polynomial(v1, v0), bins);
  }
}
} // namespace detail
} // namespace vpLaserSolvers
