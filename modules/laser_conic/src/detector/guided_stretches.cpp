/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The stretches of the final conic measured as a whole: the image's brightness R + G + B read across the curve
// at every pixel of arc, averaged over RidgeTuning::stretchHalfLength pixels on each side of a point, and a
// stripe (a Gaussian of the observed width over a quadratic background) fitted to that mean profile. Where a
// faint ring went through strong JPEG compression, each profile of the guided pass holds its stripe only as
// the low frequencies of the 8 x 8 luma blocks, whose peak lies up to 2-3 px off the line or splits; but the
// line crosses the blocks at every phase along a stretch, and the mean of ~50 px of profiles holds it (the
// faint frame 56 of `make-laser-sequence --hard --seed 19`: every 48 px stretch at 3 sigma or more within
// 0.84 px, where the points were 1-3.5 px inside). The points whose stretch tells another offset are moved to it,
// and the gaps of a fading ring filled: only on a ring that fades (a walk started into one of its long gaps,
// guided_gaps.cpp), and points are added only in the gaps it fades into or in short gaps (an object over the
// ring hides a long stretch of it between bright ends).
#include "guided_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include <visp3/robust/vpRobustScale.h>

#include "../laser_geometry.h"
#include "guided_detail.h"
#include "ridge_tuning.h"

namespace vsp::laser_detector
{
namespace
{
//! An ellipse as centre + R diag(ra, rb) (cos t, sin t).
struct EllipseFrame
{
  Eigen::Vector2d centre;
  Eigen::Matrix2d axes; //!< unit axes, as columns
  double ra = 0.0, rb = 0.0;
  Eigen::Vector2d at(double t) const { return centre + axes * Eigen::Vector2d(ra * std::cos(t), rb * std::sin(t)); }
  //! The outward unit normal at parameter t.
  Eigen::Vector2d normal(double t) const
  {
    return (axes * Eigen::Vector2d(std::cos(t) / ra, std::sin(t) / rb)).normalized();
  }
  //! The parameter of the point of the ellipse in the direction of \e p from the centre.
  double parameterOf(const Eigen::Vector2d &p) const
  {
    const Eigen::Vector2d q = axes.transpose() * (p - centre);
    return std::atan2(q.y() / rb, q.x() / ra);
  }
};

bool ellipseFrame(const Eigen::Matrix3d &C, EllipseFrame &e)
{
  return vpLaserSolvers::detail::ellipseAxes(C, e.centre, e.axes, e.ra, e.rb);
}

//! R + G + B at (u, v), bilinear between the pixel centres.
double brightnessAt(const vpImage<vpRGBa> &I, double u, double v)
{
  const int u0 = static_cast<int>(std::floor(u)), v0 = static_cast<int>(std::floor(v));
  const double fu = u - u0, fv = v - v0;
  const auto b = [&I](int r, int c) {
    const vpRGBa &p = I[r][c];
    return static_cast<double>(p.R + p.G + p.B);
  };
  return (1.0 - fv) * ((1.0 - fu) * b(v0, u0) + fu * b(v0, u0 + 1)) +
         fv * ((1.0 - fu) * b(v0 + 1, u0) + fu * b(v0 + 1, u0 + 1));
}

//! The curve at a pixel of arc: its point, outward normal and, when its profile lies inside the image, that
//! profile (RidgeTuning::stretchReach pixels on each side).
struct ArcPixel
{
  double t = 0.0; //!< parameter on the ellipse
  Eigen::Vector2d point, normal;
  bool inside = false;
  double profile[2 * RidgeTuning::stretchReach + 1];
};

//! The ellipse at every pixel of arc (a full turn from parameter 0), each with its profile across the curve.
std::vector<ArcPixel> profilesAlong(const vpImage<vpRGBa> &I, const EllipseFrame &e)
{
  std::vector<ArcPixel> arc;
  const int W = static_cast<int>(I.getWidth()), H = static_cast<int>(I.getHeight());
  // An ellipse whose perimeter (Ramanujan's approximation) is many times the image's: no ring of this image (its
  // arc, mostly outside, would be millions of pixels).
  const double perimeter = vpLaserSolvers::detail::ellipsePerimeter(e.ra, e.rb);
  if (!(perimeter <= RidgeTuning::stretchMaxPerimeter * (W + H)))
    return arc;
  arc.reserve(static_cast<size_t>(perimeter) + 1);
  const double reach = RidgeTuning::stretchReach + 1.0;
  double t = 0.0;
  while (t < 2.0 * M_PI) {
    ArcPixel a;
    a.t = t;
    a.point = e.at(t);
    a.normal = e.normal(t);
    const Eigen::Vector2d lo = a.point - reach * a.normal, hi = a.point + reach * a.normal;
    a.inside = std::min(lo.x(), hi.x()) >= 0.0 && std::min(lo.y(), hi.y()) >= 0.0 &&
               std::max(lo.x(), hi.x()) < W - 1.0 && std::max(lo.y(), hi.y()) < H - 1.0;
    for (int j = -RidgeTuning::stretchReach; a.inside && j <= RidgeTuning::stretchReach; ++j) {
      const Eigen::Vector2d p = a.point + j * a.normal;
      a.profile[j + RidgeTuning::stretchReach] = brightnessAt(I, p.x(), p.y());
    }
    arc.push_back(a);
    const Eigen::Vector2d speed = e.axes * Eigen::Vector2d(-e.ra * std::sin(t), e.rb * std::cos(t));
    t += 1.0 / std::max(1.0, speed.norm());
  }
  return arc;
}

//! A stripe fitted to a mean profile: its offset across the curve, its amplitude over the background and that
//! amplitude's significance (amplitude / its standard error).
struct RidgeFit
{
  double offset = 0.0, amplitude = 0.0, significance = 0.0;
  double rss = 0.0; //!< residual sum of squares of the fit (grey levels squared)
  bool found = false;
};

/*!
  The least-squares design of a stripe of width \e width (half-maximum, pixels) over a quadratic background,
  profile = a g(x - d) + b0 + b1 x + b2 x^2 / reach, for every offset d of a grid of quarter pixels within
  RidgeTuning::stretchMaxOffset of the curve: its samples across the curve and its factorised normal matrix,
  the same for every stretch of a measurement (their exponentials were most of its time).
*/
struct StripeDesign
{
  static constexpr int n = 2 * RidgeTuning::stretchReach + 1;
  static constexpr double step = 0.25;
  //! The stripe and a background of degree 2. A faint stretch's mean profile often lies in a shallow trough
  //! 20 px wide (the floor's texture averaged along the stretch, JPEG's blocks): a straight background took the
  //! trough's rims for its level and the stripe's amplitude for a third of its height (the faint frame of the
  //! hard sequence, seed 19: 2.5 grey levels at 1.9 standard errors for a stripe 7 above its trough).
  static constexpr int kTerms = 4;
  double sigma;
  std::vector<double> offsets;
  std::vector<Eigen::Matrix<double, n, kTerms> > X;
  std::vector<Eigen::LDLT<Eigen::Matrix<double, kTerms, kTerms> > > ldlt;
  std::vector<unsigned char> usable; //!< the normal matrix is regular
  explicit StripeDesign(double width) : sigma(std::max(0.5, width / 2.3548))
  {
    for (double d = -RidgeTuning::stretchMaxOffset; d <= RidgeTuning::stretchMaxOffset + 1e-9; d += step) {
      Eigen::Matrix<double, n, kTerms> x;
      for (int j = 0; j < n; ++j) {
        const double u = j - RidgeTuning::stretchReach, z = (u - d) / sigma;
        x.row(j) << std::exp(-0.5 * z * z), 1.0, u, u * u / RidgeTuning::stretchReach;
      }
      const Eigen::Matrix<double, kTerms, kTerms> normal = x.transpose() * x;
      offsets.push_back(d);
      X.push_back(x);
      ldlt.emplace_back(normal);
      usable.push_back(ldlt.back().info() == Eigen::Success && std::fabs(normal.determinant()) > 1e-12 ? 1 : 0);
    }
  }
  // The fit at offset k: false when its system is singular. Coefficients (a, b0, b1, b2) in \e p, the residual sum
  // of squares in \e rss, the variance of a in \e varA.
  bool fit(const double *profile, size_t k, Eigen::Matrix<double, kTerms, 1> &p, double &rss, double &varA) const
  {
    if (!usable[k])
      return false;
    const Eigen::Map<const Eigen::Matrix<double, n, 1> > y(profile);
    p = ldlt[k].solve(X[k].transpose() * y);
    rss = (y - X[k] * p).squaredNorm();
    varA = ldlt[k].solve(Eigen::Matrix<double, kTerms, 1>::Unit(0))(0) * rss / (n - kTerms);
    return std::isfinite(rss);
  }
};

// The stripe of \e design best fitted to \e profile: the offset of the grid with the least residual, then the
// vertex of the parabola through the residuals around it. A step in the background (a colour edge) is not a
// stripe: the background's change across the stripe must stay under half its amplitude.
RidgeFit fitStripe(const double *profile, const StripeDesign &design)
{
  RidgeFit best; // amplitude 0 until a stripe is fitted: only a positive amplitude is taken
  double prev = 0.0, bestPrev = 0.0, bestNext = 0.0;
  bool bestIsLast = false;
  for (size_t k = 0; k < design.offsets.size(); ++k) {
    Eigen::Matrix<double, StripeDesign::kTerms, 1> p;
    double rss = 0.0, varA = 0.0;
    if (!design.fit(profile, k, p, rss, varA)) {
      prev = 0.0;
      continue;
    }
    if (bestIsLast)
      bestNext = rss;
    bestIsLast = false;
    if (p(0) > 0.0 && (best.amplitude <= 0.0 || rss < best.rss)) {
      best = RidgeFit{design.offsets[k], p(0), p(0) / std::sqrt(std::max(varA, 1e-300)), rss, true};
      const double stepAcross = std::fabs(p(2)) * 2.0 * RidgeTuning::stretchStepWidth * design.sigma;
      best.found = stepAcross <= 0.5 * p(0);
      bestPrev = prev;
      bestIsLast = true;
      bestNext = 0.0;
    }
    prev = rss;
  }
  const double curvature = bestPrev + bestNext - 2.0 * best.rss;
  if (best.found && bestPrev > 0.0 && bestNext > 0.0 && curvature > 0.0)
    best.offset += StripeDesign::step * std::max(-0.5, std::min(0.5, 0.5 * (bestPrev - bestNext) / curvature));
  return best;
}

/*!
  The designs of the stripe widths a stretch is fitted with: the observed width \e width (that of the colour
  crossings, see GuidedSettings::stripeWidth) and every narrower one 2 px apart down to 3 px. The stretches read
  the brightness, whose stripe keeps the luma's full resolution where JPEG halves the colour's: through quality
  60 a faint ring's colour crossings measured 7 px, its brightness 3-4 px at half maximum, and the 7 px design
  over a quadratic background fitted a trough beside the stripe rather than the stripe.
*/
std::vector<StripeDesign> stripeDesigns(double width)
{
  std::vector<StripeDesign> designs;
  designs.emplace_back(width);
  for (double w = width - 2.0; w >= 3.0 - 1e-9; w -= 2.0)
    designs.emplace_back(w);
  return designs;
}

// The best fit of fitStripe() over \e designs: the least residual of those that fit a stripe (a positive amplitude).
RidgeFit fitStripe(const double *profile, const std::vector<StripeDesign> &designs)
{
  RidgeFit best;
  for (const StripeDesign &design : designs) {
    const RidgeFit fit = fitStripe(profile, design);
    if (fit.amplitude > 0.0 && (best.amplitude <= 0.0 || fit.rss < best.rss))
      best = fit;
  }
  return best;
}

// The index of the pixel of \e arc (increasing parameters) nearest below the parameter of \e p.
int arcIndexOf(const std::vector<ArcPixel> &arc, const EllipseFrame &e, const Eigen::Vector2d &p)
{
  double t = e.parameterOf(p);
  if (t < 0.0)
    t += 2.0 * M_PI;
  const auto after = std::upper_bound(arc.begin(), arc.end(), t, [](double x, const ArcPixel &a) { return x < a.t; });
  return std::max(0, static_cast<int>(after - arc.begin()) - 1);
}

//! Prefix sums, along the arc, of the profiles (one column per pixel across) and of the count inside the image.
struct ArcSums
{
  static constexpr int width = 2 * RidgeTuning::stretchReach + 1;
  std::vector<double> sum; //!< (n + 1) x width
  std::vector<int> inside; //!< n + 1
  int n = 0;
  explicit ArcSums(const std::vector<ArcPixel> &arc) : n(static_cast<int>(arc.size()))
  {
    sum.assign((arc.size() + 1) * width, 0.0);
    inside.assign(arc.size() + 1, 0);
    for (int i = 0; i < n; ++i) {
      const ArcPixel &a = arc[static_cast<size_t>(i)];
      inside[i + 1] = inside[i] + (a.inside ? 1 : 0);
      for (int j = 0; j < width; ++j)
        sum[(i + 1) * width + j] = sum[i * width + j] + (a.inside ? a.profile[j] : 0.0);
    }
  }
  // Adds the profiles of [first, last] (0 <= first <= last < n) to \e mean; returns how many are inside.
  int add(int first, int last, double *mean) const
  {
    for (int j = 0; j < width; ++j)
      mean[j] += sum[(last + 1) * width + j] - sum[first * width + j];
    return inside[last + 1] - inside[first];
  }
  // The mean profile of the pixels of arc [centre - half, centre + half] (around the turn): false unless all of
  // them are inside the image.
  bool meanAround(int centre, int half, double *profile) const
  {
    return meanOver(centre - half, centre + half, profile);
  }
  // The same over [first, last] (first <= last, less than a turn apart, either possibly beyond [0, n)).
  bool meanOver(int first, int last, double *profile) const
  {
    std::fill(profile, profile + width, 0.0);
    const int length = last - first;
    first = ((first % n) + n) % n;
    last = first + length;
    int count = 0;
    if (last >= n)
      count = add(first, n - 1, profile) + add(0, last - n, profile);
    else
      count = add(first, last, profile);
    if (count != last - first + 1)
      return false;
    for (int j = 0; j < width; ++j)
      profile[j] /= count;
    return true;
  }
};

// Whether the two halves of the stretch around \e centre hold the stripe \e fit found over it: each one's stripe
// found within RidgeTuning::stretchHalvesAgreement pixels of it, at an amplitude within a factor
// RidgeTuning::stretchHalvesRatio of the other's. A stretch across an object's edge over the ring (the stripe on
// the floor on one side, on the object or nowhere on the other) is two things, not a stripe.
bool oneStripe(const ArcSums &sums, int centre, int half, const std::vector<StripeDesign> &designs, const RidgeFit &fit)
{
  double profile[ArcSums::width];
  RidgeFit halves[2];
  for (int h = 0; h < 2; ++h) {
    if (!sums.meanOver(h == 0 ? centre - half : centre, h == 0 ? centre : centre + half, profile))
      return false;
    halves[h] = fitStripe(profile, designs);
    if (!halves[h].found || std::fabs(halves[h].offset - fit.offset) > RidgeTuning::stretchHalvesAgreement)
      return false;
  }
  const double ratio = halves[0].amplitude / halves[1].amplitude;
  return ratio <= RidgeTuning::stretchHalvesRatio && ratio >= 1.0 / RidgeTuning::stretchHalvesRatio;
}

// A crossing at \e p, measured across a curve of normal \e normal (for the mask: the line that crosses it more
// steeply).
Crossing crossingAt(const Eigen::Vector2d &p, const Eigen::Vector2d &normal)
{
  Crossing x;
  x.point = vpImagePoint(p.y(), p.x());
  x.alongRow = std::fabs(normal.x()) >= std::fabs(normal.y());
  x.line = static_cast<int>(std::lround(x.alongRow ? p.y() : p.x()));
  x.first = x.last = static_cast<int>(std::lround(x.alongRow ? p.x() : p.y()));
  return x;
}

//! The points along the pixels of arc: the crossings of the guided pass (indices from 0), then the first pass's
//! anchors (from the crossings' count; never moved).
struct ArcPoints
{
  const std::vector<Crossing> &guided;
  const std::vector<vpImagePoint> &anchors;
  std::vector<std::vector<int> > byIndex; //!< the points at each pixel of arc
  ArcPoints(const std::vector<ArcPixel> &arc, const EllipseFrame &e, const std::vector<Crossing> &guided_,
            const std::vector<vpImagePoint> &anchors_)
    : guided(guided_), anchors(anchors_), byIndex(arc.size())
  {
    for (size_t i = 0; i < guided.size() + anchors.size(); ++i)
      byIndex[static_cast<size_t>(arcIndexOf(arc, e, at(static_cast<int>(i))))].push_back(static_cast<int>(i));
  }
  Eigen::Vector2d at(int x) const
  {
    const vpImagePoint &p = static_cast<size_t>(x) < guided.size() ? guided[static_cast<size_t>(x)].point
                                                                   : anchors[static_cast<size_t>(x) - guided.size()];
    return Eigen::Vector2d(p.get_u(), p.get_v());
  }
  bool movable(int x) const { return static_cast<size_t>(x) < guided.size(); }
  /*!
    The median offset from the conic C of the points within \e reach pixels of arc of \e i (NaN without any);
    their indices in \e here.
  */
  double near(const Eigen::Matrix3d &C, int i, int reach, std::vector<int> &here, std::vector<double> &offsets) const
  {
    const int n = static_cast<int>(byIndex.size());
    offsets.clear();
    here.clear();
    for (int k = i - reach; k <= i + reach; ++k)
      for (int x : byIndex[static_cast<size_t>((k + n) % n)]) {
        here.push_back(x);
        // Signed Sampson distance, outward positive; 0 at the centre (no gradient), where no ring point lies.
        const double offset = vpLaserSolvers::detail::signedSampson(C, at(x));
        offsets.push_back(std::isfinite(offset) ? offset : 0.0);
      }
    return offsets.empty() ? std::numeric_limits<double>::quiet_NaN() : median(offsets);
  }
};

/*!
  The pixels of arc where a stretch may fill a gap: those of the gaps the ring fades into (the points of \e faded)
  and within two samples of one, and those of the short gaps (a point of \e points within
  RidgeTuning::guidedGapLength / 2 pixels of arc).
*/
std::vector<unsigned char> fillablePixels(const std::vector<ArcPixel> &arc, const EllipseFrame &e,
                                          const std::vector<vpImagePoint> &faded, const ArcPoints &points, int step)
{
  const int n = static_cast<int>(arc.size()), shortGap = static_cast<int>(RidgeTuning::guidedGapLength / 2);
  std::vector<unsigned char> fillable(arc.size(), 0);
  const auto mark = [&](int at, int reach) {
    for (int k = at - reach; k <= at + reach; ++k)
      fillable[static_cast<size_t>((k + n) % n)] = 1;
  };
  for (const vpImagePoint &p : faded)
    mark(arcIndexOf(arc, e, Eigen::Vector2d(p.get_u(), p.get_v())), 2 * step);
  for (int i = 0; i < n; ++i)
    if (!points.byIndex[static_cast<size_t>(i)].empty())
      mark(i, shortGap);
  return fillable;
}

/*!
  The stripe of the stretch around every \e step-th pixel of arc from \e start (fits[j] for pixel start + j step,
  around the turn), found when significant and one stripe (oneStripe()); returns the upper quartile of their
  amplitudes (the ring's), 0 when none is found.
*/
double fitStretches(const ArcSums &sums, int start, int step, double width, std::vector<RidgeFit> &fits)
{
  const std::vector<StripeDesign> designs = stripeDesigns(width);
  const int half = RidgeTuning::stretchHalfLength;
  fits.assign(static_cast<size_t>((sums.n + step - 1) / step), RidgeFit());
  std::vector<double> amplitudes;
  double profile[ArcSums::width];
  for (size_t j = 0; j < fits.size(); ++j) {
    const int i = (start + static_cast<int>(j) * step) % sums.n;
    if (!sums.meanAround(i, half, profile))
      continue;
    RidgeFit &fit = fits[j];
    fit = fitStripe(profile, designs);
    fit.found = fit.found && fit.significance >= RidgeTuning::stretchSignificance &&
                oneStripe(sums, i, half, designs, fit);
    if (fit.found)
      amplitudes.push_back(fit.amplitude);
  }
  if (amplitudes.empty())
    return 0.0;
  const size_t quartile = amplitudes.size() * 3 / 4;
  std::nth_element(amplitudes.begin(), amplitudes.begin() + static_cast<std::ptrdiff_t>(quartile), amplitudes.end());
  return amplitudes[quartile];
}
/*!
  The noise of one pixel's brightness beside the ring: the robust spread (vpRobustMadScale()) of the differences
  between pixels of arc two apart (bilinear samples one apart share pixels) at the profiles' two ends,
  RidgeTuning::stretchReach pixels on either side of the curve, over sqrt 2. 0 with fewer than 20 of them.
*/
double pixelNoiseBeside(const std::vector<ArcPixel> &arc)
{
  std::vector<double> differences;
  differences.reserve(2 * arc.size());
  for (size_t i = 2; i < arc.size(); ++i) {
    const ArcPixel &a = arc[i - 2], &b = arc[i];
    if (!a.inside || !b.inside)
      continue;
    differences.push_back(a.profile[0] - b.profile[0]);
    differences.push_back(a.profile[ArcSums::width - 1] - b.profile[ArcSums::width - 1]);
  }
  if (differences.size() < 20)
    return 0.0;
  return vpRobustMadScale(std::move(differences)) / std::sqrt(2.0);
}
} // namespace

int measureStretches(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const Eigen::Matrix3d &conic,
                     const std::vector<vpImagePoint> &anchors, const std::vector<vpImagePoint> &faded,
                     std::vector<Crossing> &guided)
{
  EllipseFrame e;
  if (guided.empty() || !ellipseFrame(conic, e))
    return 0;
  // Outward positive offsets: the conic's sign such that its centre is inside (negative).
  const Eigen::Vector3d c(e.centre.x(), e.centre.y(), 1.0);
  const Eigen::Matrix3d C = c.dot(conic * c) < 0.0 ? conic : Eigen::Matrix3d(-conic);
  const std::vector<ArcPixel> arc = profilesAlong(I, e);
  const int n = static_cast<int>(arc.size()), step = std::max(1, settings.step);
  if (n < 4 * RidgeTuning::stretchHalfLength)
    return 0;
  const ArcPoints points(arc, e, guided, anchors);
  const std::vector<unsigned char> fillable = fillablePixels(arc, e, faded, points, step);
  // Around the turn from a pixel of arc with points, each stretch's stripe in turn. A gap (no point within a
  // sample) is filled where the ring fades (a walk started into it) or where it is short (points within
  // RidgeTuning::guidedGapLength / 2 pixels of arc), and only where the stripe continues the last one taken
  // (RidgeTuning::stretchGapContinuity; before the gap, the stretch's stripe where there are points): beside an
  // object over the ring its shading fitted a stripe 4.5 px off, from the first stretch of the gap on.
  int start = 0;
  while (start < n && points.byIndex[static_cast<size_t>(start)].empty())
    ++start;
  std::vector<RidgeFit> fits;
  const double bright = fitStretches(ArcSums(arc), start % n, step, settings.stripeWidth, fits);
  const double faint = RidgeTuning::stretchFaintShare * bright, dim = RidgeTuning::stretchDimShare * bright;
  const double pixelNoise = pixelNoiseBeside(arc);
  const double fillLevel = RidgeTuning::stretchMinPixelSnr * pixelNoise,
               moveLevel = RidgeTuning::stretchMoveSnr * pixelNoise;
  std::vector<unsigned char> moved(guided.size(), 0);
  std::vector<Crossing> added;
  std::vector<int> here;
  std::vector<double> offsets;
  double lastOffset = std::numeric_limits<double>::quiet_NaN();
  int lastAt = 0;
  for (size_t j = 0; j < fits.size() && bright > 0.0; ++j) {
    const int i = (start + static_cast<int>(j) * step) % n, at = static_cast<int>(j) * step;
    const RidgeFit &fit = fits[j];
    const double there = points.near(C, i, step, here, offsets);
    const bool usable = fit.found && fit.amplitude >= faint && fit.amplitude >= fillLevel;
    if (!std::isnan(there)) {
      // Points there: moved to the stretch's stripe when it is dim (but stands out of the pixels' noise) and
      // elsewhere.
      const bool move = usable && fit.amplitude <= dim && fit.amplitude >= moveLevel &&
                        std::fabs(there - fit.offset) > RidgeTuning::stretchAgreement;
      lastOffset = usable ? fit.offset : there;
      lastAt = at;
      if (!move)
        continue;
    } else {
      const double tolerance = RidgeTuning::stretchGapContinuity + RidgeTuning::stretchGapDrift * (at - lastAt);
      if (!usable || !fillable[static_cast<size_t>(i)] || std::isnan(lastOffset) ||
          std::fabs(fit.offset - lastOffset) > tolerance)
        continue;
      lastOffset = fit.offset;
      lastAt = at;
    }
    for (int x : here)
      if (points.movable(x))
        moved[static_cast<size_t>(x)] = 1;
    const ArcPixel &a = arc[static_cast<size_t>(i)];
    added.push_back(crossingAt(a.point + fit.offset * a.normal, a.normal));
  }
  size_t kept = 0;
  for (size_t i = 0; i < guided.size(); ++i)
    if (!moved[i])
      guided[kept++] = guided[i];
  guided.resize(kept);
  guided.insert(guided.end(), added.begin(), added.end());
  return static_cast<int>(added.size());
}
} // namespace vsp::laser_detector
