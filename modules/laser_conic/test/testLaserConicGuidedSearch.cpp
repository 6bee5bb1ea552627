/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of the conic-guided second pass of vpLaserConicDetector against the simulator's ground truth: rings
// that fade along their length (distance and incidence fall-off, down to 10 % of the peak), laser light
// scaled by the floor's reflectance, JPEG compression; the coverage of the part of the ring where the
// stripe is at least 3 times the sensor noise, the precision of all the points and the accuracy of the
// second pass's ones; distractors; tracking with the previous frame's conic.
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>

#include "laser_sim_test_utils.h"

using namespace laser_sim_test;

namespace
{
typedef vpLaserConicSimulator::vpRenderSettings Settings;

//! A fading ring as the dark-room photographs show it: \e nearPeak grey levels of red dominance on the near
//! side, \e farPeak on the far side, noise 2, JPEG at quality 90.
Settings fadingRing(double nearPeak, double farPeak)
{
  Settings s;
  s.ambient = 0.3;
  s.laserPower = nearPeak;
  s.distanceFalloff = 2.0;
  s.lambertIncidence = true;
  s.stripeFarFraction = farPeak / nearPeak;
  s.stripeWidth = 3.0;
  s.noise = 2.0;
  s.jpegQuality = 90;
  return s;
}

//! The noise seeds of the faint-ring tests.
const std::vector<unsigned int> kFaintSeeds = {72u, 60u, 61u, 62u, 63u, 64u, 65u};

//! The fading ring on the colourful mosaic floor, the laser light scaled by its red reflectance.
Settings fadingMosaic()
{
  Settings s = fadingRing(150.0, 20.0);
  s.floor = vpLaserConicSimulator::FLOOR_MOSAIC;
  s.ambient = 0.6;
  s.reflectanceScaled = true;
  return s;
}

//! A tilted ground (30 deg): distance and incidence vary along the ring.
vpHomogeneousMatrix tiltedGround()
{
  return vpHomogeneousMatrix(0.05, -0.03, 1.0, vpMath::rad(30), vpMath::rad(-8), 0.3);
}

//! The ground point (X, Y) of the ground frame seen by the image point \e p of the undistorted camera \e cam.
void groundPointOf(const vpCameraParameters &cam, const vpHomogeneousMatrix &cMg, const vpImagePoint &p, double g[2])
{
  const vpColVector ray({(p.get_u() - cam.get_u0()) / cam.get_px(), (p.get_v() - cam.get_v0()) / cam.get_py(), 1.0});
  const vpColVector n({cMg[0][2], cMg[1][2], cMg[2][2]}), t({cMg[0][3], cMg[1][3], cMg[2][3]});
  const double lambda = vpColVector::dotProd(n, t) / vpColVector::dotProd(n, ray);
  const vpHomogeneousMatrix gMc = cMg.inverse();
  const vpColVector Pc = lambda * ray;
  for (unsigned int i = 0; i < 2; ++i)
    g[i] = gMc[i][0] * Pc[0] + gMc[i][1] * Pc[1] + gMc[i][2] * Pc[2] + gMc[i][3];
}

struct GuidedQuality
{
  double coverage3 = 0.0; //!< share of the ring where the stripe is >= 3 sigma with a point within 1.5 px
  double precision = 0.0; //!< share of all the points within 1.5 px of the centre line
  double rmsGuided = 0.0; //!< RMS distance (px) of the second pass's points within 1.5 px of the line
  double guidedOff = 0.0; //!< share of the second pass's points farther than 1.5 px
  //! coverage3 over the ring seen as a ridge of the image (vpLaserConicSimulator::ridgeCoverage()); NaN unless
  //! runGuided() was asked for it (a second render of the frame)
  double ridge3 = std::numeric_limits<double>::quiet_NaN();
  //! coverage3 over the ring that the JPEG compression kept at 3 sigma (vpLaserConicSimulator::keptCoverage());
  //! NaN unless runGuided() was asked for it (four more renders of the frame)
  double kept3 = std::numeric_limits<double>::quiet_NaN();
  size_t points = 0, guided = 0;
};

//! Whether runGuided() measures GuidedQuality::ridge3.
enum class Ridges { skip, measure };
//! Whether runGuided() measures GuidedQuality::kept3.
enum class Kept { skip, measure };

//! Renders the case (seeded) through the camera \e cam, detects, measures against the ground truth.
GuidedQuality runGuided(const std::string &name, const vpHomogeneousMatrix &cMg, const Settings &s, unsigned int seed,
                        vpLaserConicDetector &detector, std::vector<vpImagePoint> *detected = nullptr,
                        Ridges ridges = Ridges::skip, const vpCameraParameters &cam = camera(), Kept kept = Kept::skip)
{
  vpLaserConicSimulator sim = makeSimulator(cMg, seed);
  sim.setCamera(cam, kWidth, kHeight);
  const vpLaserConicSimulator beforeRendering = sim; // the random draws of the render below, for Kept::measure
  vpImage<vpRGBa> I;
  sim.render(I, s);
  dumpIfRequested("guided_" + name, I);
  const std::vector<vpImagePoint> points = detector.detect(I);
  if (detected)
    *detected = points;
  std::vector<vpLaserConicSimulator::vpTraceTruth> truth = sim.traceTruth(6000, s);
  const TraceLine line(sim);
  GuidedQuality q;
  q.coverage3 = vpLaserConicSimulator::stripeCoverage(truth, points, 3.0, 1.5);
  if (ridges == Ridges::measure) {
    sim.measureProminence(truth, s);
    q.ridge3 = vpLaserConicSimulator::ridgeCoverage(truth, points, 3.0, 1.5);
  }
  if (kept == Kept::measure) {
    beforeRendering.measureCompression(truth, s);
    q.kept3 = vpLaserConicSimulator::keptCoverage(truth, points, 3.0, 1.5);
  }
  q.points = points.size();
  q.guided = detector.getGuidedPointCount();
  size_t on = 0, guidedOn = 0;
  double sum2 = 0.0;
  for (size_t k = 0; k < points.size(); ++k) {
    const double d = line.distance(points[k]);
    const bool isGuided = k >= points.size() - q.guided;
    if (d <= 1.5) {
      ++on;
      if (isGuided) {
        ++guidedOn;
        sum2 += d * d;
      }
    }
  }
  q.precision = points.empty() ? 0.0 : static_cast<double>(on) / points.size();
  q.rmsGuided = guidedOn ? std::sqrt(sum2 / guidedOn) : 0.0;
  q.guidedOff = q.guided ? 1.0 - static_cast<double>(guidedOn) / q.guided : 0.0;
  std::cout << name << ": " << q.points << " points (" << q.guided << " of the second pass), coverage >= 3 sigma "
            << 100 * q.coverage3 << " %, precision " << q.precision << ", second-pass RMS " << q.rmsGuided << " px ("
            << 100 * q.guidedOff << " % off)";
  if (ridges == Ridges::measure)
    std::cout << ", seen as a ridge: " << 100 * q.ridge3 << " %";
  if (kept == Kept::measure)
    std::cout << ", of what JPEG kept at 3 sigma: " << 100 * q.kept3 << " %";
  std::cout << std::endl;
  return q;
}

//! The exact image conic (pixels) of the trace on the ground cMg, as a tracker gets it from the previous frame.
vpMatrix imageConicOf(const vpHomogeneousMatrix &cMg)
{
  const Eigen::Matrix3d C = pixelConic(makeSimulator(cMg).getGroundPlane());
  vpMatrix Cv(3, 3);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      Cv[i][j] = C(i, j);
  return Cv;
}

//! The bounds of the guided pass on a rendered hard case: the coverage of the ring where the stripe is at
//! least 3 sigma, the precision of all the points (0.98), the RMS of the second pass's points.
void expectGuided(const GuidedQuality &q, double minCoverage, double maxRms)
{
  EXPECT_GE(q.coverage3, minCoverage);
  EXPECT_GE(q.precision, 0.98);
  EXPECT_LE(q.rmsGuided, maxRms);
}

//! Means over seeds of the coverage at 3 sigma and of the second-pass RMS.
struct SeedMeans
{
  double coverage3 = 0.0, rmsGuided = 0.0;
  double ridge3 = 0.0; //!< NaN unless the ridges were measured
  double kept3 = 0.0;  //!< NaN unless what JPEG kept was measured
};

/*!
  The case \e s on the tilted ground rendered through \e cam with each of \e seeds (run \e name_seed), \e check
  called on each seed's quality: the means over the seeds.
*/
template <class Check>
SeedMeans overSeeds(const std::string &name, const Settings &s, const std::vector<unsigned int> &seeds, Check check,
                    Ridges ridges = Ridges::skip, const vpCameraParameters &cam = camera(), Kept kept = Kept::skip)
{
  SeedMeans means;
  for (unsigned int seed : seeds) {
    vpLaserConicDetector detector;
    const GuidedQuality q =
        runGuided(name + "_" + std::to_string(seed), tiltedGround(), s, seed, detector, nullptr, ridges, cam, kept);
    check(seed, q);
    means.coverage3 += q.coverage3 / seeds.size();
    means.rmsGuided += q.rmsGuided / seeds.size();
    means.ridge3 += q.ridge3 / seeds.size();
    means.kept3 += q.kept3 / seeds.size();
  }
  return means;
}

/*!
  Share of the ring within \e radius pixels of \e centre (its part at 3 sigma or more, \e truth) that has a point
  within 1.5 px of the centre line (vpLaserConicSimulator::stripeCoverage()), printed with how many truth samples
  lie there.
*/
double coverageNear(const std::vector<vpLaserConicSimulator::vpTraceTruth> &truth,
                    const std::vector<vpImagePoint> &points, const vpImagePoint &centre, double radius)
{
  std::vector<vpLaserConicSimulator::vpTraceTruth> near;
  for (const vpLaserConicSimulator::vpTraceTruth &t : truth)
    if (vpImagePoint::distance(t.point, centre) <= radius)
      near.push_back(t);
  const double found = vpLaserConicSimulator::stripeCoverage(near, points, 3.0, 1.5);
  std::cout << "near " << centre << ": " << near.size() << " truth samples, " << 100.0 * found << " % found"
            << std::endl;
  return found;
}

//! A place of the image (i = v, j = u) and a radius around it.
struct Place
{
  vpImagePoint centre;
  double radius;
};

/*!
  The colourful mosaic (fadingMosaic(), tiltedGround()) of seed \e seed at the default settings: its quality, and
  per place of \e places the share of its ring at 3 sigma found within the radius (coverageNear()); the ring seen
  as a ridge (GuidedQuality::ridge3) measured when \e ridges asks.
*/
GuidedQuality mosaicNear(const std::string &name, unsigned int seed, const std::vector<Place> &places,
                         std::vector<double> &near, Ridges ridges = Ridges::skip)
{
  vpLaserConicDetector detector;
  std::vector<vpImagePoint> points;
  const GuidedQuality q = runGuided(name, tiltedGround(), fadingMosaic(), seed, detector, &points, ridges);
  vpLaserConicSimulator sim = makeSimulator(tiltedGround(), seed);
  const std::vector<vpLaserConicSimulator::vpTraceTruth> truth = sim.traceTruth(6000, fadingMosaic());
  near.clear();
  for (const Place &place : places)
    near.push_back(coverageNear(truth, points, place.centre, place.radius));
  return q;
}

//! \e count consecutive seeds from \e first.
std::vector<unsigned int> seedRange(unsigned int first, unsigned int count)
{
  std::vector<unsigned int> seeds(count);
  for (unsigned int k = 0; k < count; ++k)
    seeds[k] = first + k;
  return seeds;
}

//! The centroid of the truth samples (inside the ring).
vpImagePoint truthCentroid(const std::vector<vpLaserConicSimulator::vpTraceTruth> &truth)
{
  double cu = 0.0, cv = 0.0;
  for (const auto &t : truth) {
    cu += t.point.get_u() / truth.size();
    cv += t.point.get_v() / truth.size();
  }
  return vpImagePoint(cv, cu);
}

/*!
  The unit normal (nu, nv) of the centre line at truth sample k (0 < k < size - 1), pointing away from \e centre
  (outwards); false where a neighbouring sample lies 5 px or more away (a gap of the trace).
*/
bool outwardNormal(const std::vector<vpLaserConicSimulator::vpTraceTruth> &truth, size_t k, const vpImagePoint &centre,
                   double &nu, double &nv)
{
  const vpImagePoint &p = truth[k].point;
  const double tu = truth[k + 1].point.get_u() - truth[k - 1].point.get_u(),
               tv = truth[k + 1].point.get_v() - truth[k - 1].point.get_v(), length = std::hypot(tu, tv);
  if (!(length > 0.0 && length < 5.0))
    return false;
  const double side = (p.get_u() - centre.get_u()) * tv - (p.get_v() - centre.get_v()) * tu < 0.0 ? -1.0 : 1.0;
  nu = side * tv / length;
  nv = -side * tu / length;
  return true;
}

/*!
  How the second pass's points of one frame (within 1.5 px of the centre line, each against its nearest truth
  sample, where the stripe is at least 3 sigma) miss the line: the RMS by the stripe's strength there, the mean and spread of the signed error (outwards
  positive) by 15 degrees of the ring, and where the ring runs along the image columns (normal within 25 degrees of
  the u axis) the mean error in u by the truth's column modulo 16, the width of JPEG's colour blocks.
*/
struct ErrorBreakdown
{
  //! Upper bounds of the strength classes (peakOverNoise): [3, 6), [6, 10), [10, 20), [20, inf).
  static constexpr double kStrength[4] = {6.0, 10.0, 20.0, std::numeric_limits<double>::infinity()};
  double sum2[4] = {0.0, 0.0, 0.0, 0.0};
  size_t count[4] = {0, 0, 0, 0};
  double sectorSum[24] = {}, sectorSum2[24] = {};
  size_t sectorCount[24] = {};
  double phaseSum[16] = {};
  size_t phaseCount[16] = {};

  void add(const vpLaserConicSimulator::vpTraceTruth &t, double angle, double outward, double errorU, bool alongColumns)
  {
    if (!(t.peakOverNoise >= 3.0))
      return;
    const size_t c = static_cast<size_t>(std::upper_bound(kStrength, kStrength + 4, t.peakOverNoise) - kStrength);
    sum2[std::min<size_t>(c, 3)] += outward * outward;
    ++count[std::min<size_t>(c, 3)];
    const size_t sector = std::min<size_t>(23, static_cast<size_t>((angle + M_PI) / (2.0 * M_PI) * 24.0));
    sectorSum[sector] += outward;
    sectorSum2[sector] += outward * outward;
    ++sectorCount[sector];
    if (alongColumns) {
      const size_t phase = static_cast<size_t>(std::floor(std::fmod(t.point.get_u() + 0.5, 16.0)));
      phaseSum[phase] += errorU;
      ++phaseCount[phase];
    }
  }
  //! RMS (px) of the strength class c; NaN when empty.
  double rms(size_t c) const { return count[c] ? std::sqrt(sum2[c] / count[c]) : std::nan(""); }
  //! Share of the squared error that the sectors' mean errors account for: a bias that follows the ring, not noise.
  double biasShare() const
  {
    double bias = 0.0, total = 0.0;
    for (size_t k = 0; k < 24; ++k)
      if (sectorCount[k] > 0) {
        bias += sectorSum[k] * sectorSum[k] / sectorCount[k];
        total += sectorSum2[k];
      }
    return total > 0.0 ? bias / total : 0.0;
  }
  //! Largest spread (px, standard deviation) of the error about its mean within one sector of 10 points or more.
  double largestSectorSpread() const
  {
    double largest = 0.0;
    for (size_t k = 0; k < 24; ++k)
      if (sectorCount[k] >= 10) {
        const double mean = sectorSum[k] / sectorCount[k];
        largest = std::max(largest, std::sqrt(std::max(0.0, sectorSum2[k] / sectorCount[k] - mean * mean)));
      }
    return largest;
  }
  //! Largest absolute mean error (px) of a sector of 10 points or more.
  double largestSectorBias() const
  {
    double largest = 0.0;
    for (size_t k = 0; k < 24; ++k)
      if (sectorCount[k] >= 10)
        largest = std::max(largest, std::fabs(sectorSum[k] / sectorCount[k]));
    return largest;
  }
  //! Largest less smallest mean error in u (px) of the column phases with 8 points or more.
  double sawtooth() const
  {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (size_t k = 0; k < 16; ++k)
      if (phaseCount[k] >= 8) {
        lo = std::min(lo, phaseSum[k] / phaseCount[k]);
        hi = std::max(hi, phaseSum[k] / phaseCount[k]);
      }
    return hi >= lo ? hi - lo : 0.0;
  }
  void print(const std::string &name) const
  {
    std::cout << name << ": RMS by the stripe's strength, 3-6 sigma " << rms(0) << " px (" << count[0]
              << " points), 6-10 " << rms(1) << " (" << count[1] << "), 10-20 " << rms(2) << " (" << count[2]
              << "), over 20 " << rms(3) << " (" << count[3] << "); bias share " << biasShare()
              << ", largest mean error in 15 deg " << largestSectorBias() << " px, largest spread about it "
              << largestSectorSpread() << " px; mean error in u by column mod 16:";
    for (size_t k = 0; k < 16; ++k)
      if (phaseCount[k] >= 8)
        std::cout << " " << k << ":" << phaseSum[k] / phaseCount[k];
    std::cout << " (sawtooth " << sawtooth() << " px)" << std::endl;
  }
};

//! ErrorBreakdown of the faint ring (fadingRing(40, 4), tiltedGround()) of \e seed rendered with \e s.
ErrorBreakdown secondPassErrors(const std::string &name, const Settings &s, unsigned int seed)
{
  vpLaserConicDetector detector;
  std::vector<vpImagePoint> points;
  runGuided(name, tiltedGround(), s, seed, detector, &points);
  vpLaserConicSimulator sim = makeSimulator(tiltedGround(), seed);
  const std::vector<vpLaserConicSimulator::vpTraceTruth> truth = sim.traceTruth(6000, s);
  const TraceLine line(sim);
  const vpImagePoint centre = truthCentroid(truth);
  ErrorBreakdown breakdown;
  for (size_t k = points.size() - detector.getGuidedPointCount(); k < points.size(); ++k) {
    if (!(line.distance(points[k]) <= 1.5))
      continue;
    size_t nearest = 1;
    for (size_t t = 1; t + 1 < truth.size(); ++t)
      if (vpImagePoint::sqrDistance(truth[t].point, points[k]) <
          vpImagePoint::sqrDistance(truth[nearest].point, points[k]))
        nearest = t;
    double nu = 0.0, nv = 0.0;
    if (!outwardNormal(truth, nearest, centre, nu, nv))
      continue;
    const vpImagePoint &t = truth[nearest].point;
    const double du = points[k].get_u() - t.get_u(), dv = points[k].get_v() - t.get_v();
    const double angle = std::atan2(t.get_v() - centre.get_v(), t.get_u() - centre.get_u());
    breakdown.add(truth[nearest], angle, du * nu + dv * nv, du, std::fabs(nu) >= std::cos(vpMath::rad(25.0)));
  }
  breakdown.print(name);
  return breakdown;
}

// The reading of a faint stripe that knows where it is: the red dominance sampled across the true centre line,
// averaged over a stretch of arc and located by a matched filter (see TheDimSideThroughJpegHoldsItsLineToAFewTenths).

//! Samples per pixel across the line, and the half length of a profile (pixels).
constexpr int kAcrossPerPixel = 4, kAcrossHalf = 8;

/*!
  The profile of I across the true centre line at each truth sample (kAcrossPerPixel samples per pixel within
  kAcrossHalf pixels, outwards positive), empty where the sample has no neighbour within 5 px or the profile
  leaves the image; \e arc: the samples' arc length.
*/
std::vector<std::vector<double> > profilesAcross(const vpImage<vpRGBa> &I,
                                                 const std::vector<vpLaserConicSimulator::vpTraceTruth> &truth,
                                                 std::vector<double> &arc)
{
  const size_t n = truth.size();
  const vpImagePoint centre = truthCentroid(truth);
  std::vector<std::vector<double> > profiles(n);
  arc.assign(n, 0.0);
  for (size_t k = 1; k < n; ++k)
    arc[k] = arc[k - 1] + vpImagePoint::distance(truth[k].point, truth[k - 1].point);
  const int half = kAcrossPerPixel * kAcrossHalf;
  for (size_t k = 1; k + 1 < n; ++k) {
    const vpImagePoint &p = truth[k].point;
    double nu = 0.0, nv = 0.0;
    if (!outwardNormal(truth, k, centre, nu, nv))
      continue;
    std::vector<double> values;
    for (int d = -half; d <= half; ++d)
      values.push_back(redDominanceAt(I, p.get_u() + d * nu / kAcrossPerPixel, p.get_v() + d * nv / kAcrossPerPixel));
    if (std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); }))
      profiles[k].swap(values);
  }
  return profiles;
}

//! Offset (pixels) of the best response of a 3 px box against 4 px of background on each side 1 px beyond it.
double stripeOffset(const std::vector<double> &profile)
{
  const int half = kAcrossPerPixel * kAcrossHalf, box = 3 * kAcrossPerPixel / 2;
  const int gap = box + kAcrossPerPixel, far = gap + 4 * kAcrossPerPixel;
  const auto value = [&profile](int i) { return profile[static_cast<size_t>(i)]; };
  std::vector<double> response(profile.size(), -std::numeric_limits<double>::infinity());
  const auto responseAt = [&response](int i) -> double & { return response[static_cast<size_t>(i)]; };
  int best = -1;
  for (int c = far; c + far <= 2 * half; ++c) {
    double stripe = 0.0, background = 0.0;
    for (int e = -box; e <= box; ++e)
      stripe += value(c + e);
    for (int e = gap; e <= far; ++e)
      background += value(c + e) + value(c - e);
    responseAt(c) = stripe / (2 * box + 1) - background / (2 * (far - gap + 1));
    if (best < 0 || responseAt(c) > responseAt(best))
      best = c;
  }
  double offset = best - half;
  const double y0 = responseAt(best - 1), y1 = responseAt(best), y2 = responseAt(best + 1);
  if (std::isfinite(y0) && std::isfinite(y2) && y0 - 2 * y1 + y2 < 0.0)
    offset += 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2);
  return offset / kAcrossPerPixel;
}

/*!
  RMS (pixels) of the stripe's offset from the true centre line read on the profiles averaged over \e length
  pixels of arc, at every tenth truth sample whose stripe is between \e lo and \e hi times the noise.
*/
double trueLineReadingRms(const vpImage<vpRGBa> &I, const std::vector<vpLaserConicSimulator::vpTraceTruth> &truth,
                          double length, double lo, double hi)
{
  std::vector<double> arc;
  const std::vector<std::vector<double> > profiles = profilesAcross(I, truth, arc);
  double sum2 = 0.0;
  size_t count = 0;
  for (size_t k = 0; k < truth.size(); k += 10) {
    if (profiles[k].empty() || truth[k].peakOverNoise < lo || truth[k].peakOverNoise >= hi)
      continue;
    std::vector<double> average(profiles[k].size(), 0.0);
    for (size_t j = 0; j < truth.size(); ++j)
      if (!profiles[j].empty() && std::fabs(arc[j] - arc[k]) <= 0.5 * length)
        for (size_t d = 0; d < average.size(); ++d)
          average[d] += profiles[j][d];
    const double offset = stripeOffset(average);
    sum2 += offset * offset;
    ++count;
  }
  return count ? std::sqrt(sum2 / count) : std::numeric_limits<double>::quiet_NaN();
}
} // namespace

TEST(LaserConicGuidedSearch, FadingRingOnADarkFloorIsFoundAllRound)
{
  // 150 grey levels near, 15 far (7.5 sigma): the first pass, whose threshold is 5 times the noise of the
  // whole image over the stripe width, keeps the bright arcs (73 % of the ring, see
  // SettingsAreCheckedAndTheSecondPassCanBeTurnedOff); over the whole image the sample of rows locates the
  // ring and the second pass measures it: measured 100 %, precision 1, second-pass RMS 0.062-0.065 px over
  // 2370-2372 of 2530-2532 points (0.076-0.084 px with the regularisation along 40 px of arc instead of 80,
  // 0.10-0.11 px along 20;
  // 0.17-0.18 px when it filled the gaps of the full first pass only; the bounds: 95 %, 0.98, 0.3 px).
  // Measured one profile at a time the dim side's centres were off by 0.39-0.42 px RMS; JPEG alone (no
  // sensor noise) left 0.45 px: its error follows the 8 x 8 blocks, so only the regularisation along 20 px
  // of arc averages it out (within 8 px it did not).
  for (unsigned int seed : {70u, 71u}) {
    vpLaserConicDetector detector;
    const GuidedQuality q = runGuided("fading_dark", tiltedGround(), fadingRing(150.0, 15.0), seed, detector);
    expectGuided(q, 0.95, 0.3);
    EXPECT_GT(q.guided, 100u); // the first pass alone misses the far side
  }
}

TEST(LaserConicGuidedSearch, FaintRingDownToTwiceTheNoise)
{
  // 40 near, 4 far (2 sigma), seven noise seeds. Of the part of the ring at 3 sigma or more, measured 98.9-99.93 %
  // found (mean 99.54 %), precision 1, second-pass RMS 0.15-0.26 px (mean 0.191; 0.17-0.28 px, mean 0.202,
  // before the short pieces standing alone on the far side were dropped, RidgeTuning::guidedIsolatedRun; 0.196
  // before the walk into long gaps on the brightness, walkIntoLongGaps(), 0.201 before that walk bridged its
  // misses, RidgeTuning::guidedWalkGap). Before a point measured at the
  // prediction had to be a peak of the response inside its window (ProfileWindow::peakWithin): 0.17-0.31 px, mean
  // 0.209, seed 60 over the 0.3 px with far-side points placed on the flank of the stripe at the window's
  // end. Every seed is held to the bounds, the means to the measured ones with a margin. What is
  // missed lies between 3 and 3.3 sigma,
  // where JPEG at quality 90 leaves a matched-filter response of 0-2 grey levels per line (it rounds the weak
  // chroma detail away; without JPEG 99.1 % is found for seed 72): a profile averages nine lines where three
  // find nothing, a followed stripe lost on the red score is searched on its brightness, and so is the
  // prediction where it crosses a step of the tiles' colour. The Cramer-Rao
  // bound of one three-line profile there (Gaussian stripe of 3 px FWHM, peak 6 over a dominance noise of 2.6)
  // is 0.30 px: the regularisation along the curve is what brings the RMS under it. (How each step of the
  // guided pass moved these figures: CHANGELOG.md.)
  const SeedMeans means = overSeeds("faint", fadingRing(40.0, 4.0), kFaintSeeds,
                                    [](unsigned int, const GuidedQuality &q) { expectGuided(q, 0.95, 0.3); });
  EXPECT_GE(means.coverage3, 0.99);
  EXPECT_LE(means.rmsGuided, 0.21);
}

TEST(LaserConicGuidedSearch, NoCentreIsReturnedTwice)
{
  // A walk along a refitted conic measures again the samples whose prediction moved along their line by more than
  // a pixel (on the dim side, where the refits move most) and finds the same centres: the faint ring's seed 60
  // returned 28 centres twice or more, seed 117 through the wide lens 29 (never-tuned, its second-pass RMS 0.344
  // px with them counted, 0.331 px without), one measurement counted up to four times by an estimate from the
  // points. Each centre is returned once now; where the points lie is the same (the coverage of every case of this
  // file unchanged).
  const std::vector<std::pair<unsigned int, vpCameraParameters> > cases = {{60u, camera()}, {117u, wideCamera()}};
  for (const auto &c : cases) {
    vpLaserConicDetector detector;
    std::vector<vpImagePoint> points;
    const GuidedQuality q = runGuided("faint_repeats_" + std::to_string(c.first), tiltedGround(), fadingRing(40.0, 4.0),
                                      c.first, detector, &points, Ridges::skip, c.second);
    std::vector<std::pair<double, double> > centres;
    centres.reserve(points.size());
    for (const vpImagePoint &p : points)
      centres.emplace_back(p.get_u(), p.get_v());
    std::sort(centres.begin(), centres.end());
    EXPECT_EQ(std::adjacent_find(centres.begin(), centres.end()), centres.end()) << "seed " << c.first;
    expectGuided(q, 0.95, 0.35);
  }
}

TEST(LaserConicGuidedSearch, AStretchBarelyOutOfThePixelsNoiseNeitherFillsNorMoves)
{
  // The faint ring above on seed 104, one of the never-tuned seeds (DISABLED_SeedsNeverTunedOn): its far side at
  // 1.6-2.3 sigma, where the final ellipse's stretches, averaged over 48 px of arc, found a stripe significant
  // at 7-19 standard errors but only 1.3-3.6 times the noise of one pixel's brightness. Their fills lay 1.0-1.3 px
  // off the line and one moved five points to 1.6-1.7 px off it: second-pass RMS 0.334 px, over the issue's
  // 0.3 px (0.268 px with a straight background under the stretches' stripe, which fitted fewer of them). Since
  // fills need 2.2 and moves 4.4 times that noise (RidgeTuning::stretchMinPixelSnr, stretchMoveSnr): 0.268 px,
  // 99.49 % of the ring at 3 sigma, precision 0.9995.
  vpLaserConicDetector detector;
  const GuidedQuality q = runGuided("faint_104", tiltedGround(), fadingRing(40.0, 4.0), 104u, detector);
  expectGuided(q, 0.95, 0.3);
}

TEST(LaserConicGuidedSearch, FaintRingThroughAWideDistortedLens)
{
  // The faint ring above through the wide lens with barrel distortion (wideCamera()): the image of the trace is
  // not a conic, and the guided pass's prediction and its regularisation along the fitted ellipse follow it only
  // to within its distortion. Measured on the same seven seeds: 97.2-99.8 % of the ring at 3 sigma (mean
  // 98.75 %), precision >= 0.997, second-pass RMS 0.12-0.26 px (mean 0.206): the bounds hold on every
  // seed. Seed 61 was at 0.329 px until the short pieces that stand alone were dropped
  // (RidgeTuning::guidedIsolatedRun): 40 % of its squared error came from 19 points where the stripe is at
  // 1.6-1.8 sigma, most of them a piece of 12 points 1.4 px beside the ring with nothing found within 30 px
  // of it (rendered without JPEG: 0.030 px, precision 1). Before: seed 61 0.351 px before
  // RidgeTuning::guidedEdgeBump; 96.5-99.6 %, mean 98.57 %, precision 1, 0.14-0.36 px, mean 0.214, before
  // walkIntoLongGaps(); 0.991-1 and 0.15-0.33 px, mean 0.246, before ProfileWindow::peakWithin. The means'
  // bounds are the measured ones with a margin. Twenty more seeds: DISABLED_SeedsNeverTunedOn.
  std::vector<unsigned int> seeds = kFaintSeeds;
  seeds.resize(static_cast<size_t>(laser_test::trials(7, 2))); // two under the sanitizers
  const SeedMeans means = overSeeds(
      "faint_wide", fadingRing(40.0, 4.0), seeds,
      [](unsigned int, const GuidedQuality &q) { expectGuided(q, 0.95, 0.3); }, Ridges::skip, wideCamera());
  EXPECT_GE(means.coverage3, 0.98);
  EXPECT_LE(means.rmsGuided, 0.23);
}

TEST(LaserConicGuidedSearch, AFaintRingThroughStrongJpegIsFollowedIntoItsDimSideOnItsBrightness)
{
  // The faint ring above through JPEG at quality 60 (the default of make-laser-sequence --hard): the colour,
  // stored at half resolution, keeps too little of the dim side's red dominance, and the walks along the
  // ellipse of the bright arcs leave a long gap there; the final conic's gaps are then followed on the
  // brightness from their dim ends (walkIntoLongGaps()). Measured on seeds 72, 60 and 65: 91.97, 96.06 and
  // 93.56 % of the ring at 3 sigma (mean 93.86 %); 91.20, 93.41 and 91.68 % (mean 92.10 %) when the walk
  // stopped at four misses in a row (RidgeTuning::guidedWalkGap), 88.20, 89.86 and 89.80 % (mean 89.29 %)
  // without that walk; precision 0.981-0.987 each time; second-pass RMS 0.35-0.40 px (0.34-0.44 px before;
  // JPEG 60's colour blocks move the centres, as at 90 on a smaller scale:
  // TheDimSideThroughJpegHoldsItsLineToAFewTenths). Part of what is missed is not in the image: over the ring
  // where what the compression kept of the stripe's brightness is still 3 sigma
  // (vpLaserConicSimulator::keptCoverage()), 93.99, 97.51 and 97.39 % is found (mean 96.30 %). With the final
  // ellipse measured stretch by stretch where the ring fades (guided_stretches.cpp): 92.58, 97.03 and 94.83 %
  // (mean 94.81 %), of what the compression kept 94.42, 97.83 and 97.97 % (mean 96.74 %); precision
  // 0.980-0.987 (0.9777 on seed 65 while a stretch at 5 % of the ring's amplitude could fill a gap: 10 %).
  // With a quadratic background under the stretches' stripe (a faint stretch's mean profile lies in a shallow
  // trough): 93.31, 97.89 and 96.01 % (mean 95.74 %), of what the compression kept 94.73, 98.44 and 98.44 %
  // (mean 97.20 %); precision 0.982-0.987. With the stretches fitted at the brightness's width too
  // (AStretchIsFittedAtTheWidthOfItsBrightness): 93.33, 98.44 and 96.52 % (mean 96.10 %), of what the compression
  // kept 94.75, 99.03 and 98.63 % (mean 97.47 %).
  Settings s = fadingRing(40.0, 4.0);
  s.jpegQuality = 60;
  const SeedMeans means = overSeeds(
      "faint_jpeg60", s, {72u, 60u, 65u},
      [](unsigned int, const GuidedQuality &q) {
        EXPECT_GE(q.coverage3, 0.90);
        EXPECT_GE(q.precision, 0.98);
        EXPECT_GE(q.kept3, 0.93);
      },
      Ridges::skip, camera(), Kept::measure);
  EXPECT_GE(means.coverage3, 0.950);
  EXPECT_GE(means.kept3, 0.968);
}

TEST(LaserConicGuidedSearch, StrongJpegsErrorIsTheColourBlocksBiasNotNoise)
{
  // Why the second pass's RMS through JPEG 60 stays over the 0.3 px (0.35-0.42 px on the seeds above), as
  // a measurement that reruns: the same frames rendered without compression are the control. Through JPEG 60 the
  // error hardly depends on the stripe's strength (3-6, 6-10 and 10-20 sigma alike), most of it is a mean error
  // that changes slowly along the ring, not noise about it, and where the ring runs along the columns the error
  // in u follows the column modulo 16, the colour's blocks (4:2:0: 8 x 8 blocks of chroma at half resolution):
  // R - max(G, B) is chroma alone, and its blocks pull the centres. Without compression none of this is there.
  // The bounds hold the diagnosis (vpLaserConicDetector's documented limits): a change that removes the bias fails
  // them, and the limits are then to be rewritten.
  const std::vector<unsigned int> seeds = laser_test::trialsOf(std::vector<unsigned int>{72u, 60u, 65u}, 1);
  for (unsigned int seed : seeds) {
    Settings s = fadingRing(40.0, 4.0);
    s.jpegQuality = 60;
    const ErrorBreakdown jpeg = secondPassErrors("faint_jpeg60_" + std::to_string(seed), s, seed);
    s.jpegQuality = 0;
    const ErrorBreakdown raw = secondPassErrors("faint_raw_" + std::to_string(seed), s, seed);
    // Noise would fall with the stripe's strength, as it does without compression (RMS at 10-20 sigma 0.29-0.46
    // times that at 3-6 sigma); through JPEG 60 it does not (1.12-1.37 times).
    EXPECT_GE(jpeg.rms(2), 0.8 * jpeg.rms(0)) << "seed " << seed;
    EXPECT_LE(raw.rms(2), 0.6 * raw.rms(0)) << "seed " << seed;
    EXPECT_LE(raw.rms(2), 0.05) << "seed " << seed;
    // The mean error of 15 degrees of the ring: 0.62-0.71 px at its largest through JPEG 60, 0.03-0.10 px without;
    // through JPEG 60, 78-83 % of the squared error.
    EXPECT_GE(jpeg.largestSectorBias(), 0.45) << "seed " << seed;
    EXPECT_LE(raw.largestSectorBias(), 0.15) << "seed " << seed;
    EXPECT_GE(jpeg.biasShare(), 0.6) << "seed " << seed;
    // The 16 px sawtooth: 0.40-0.58 px from its top to its bottom through JPEG 60, 0.03-0.04 px without.
    EXPECT_GE(jpeg.sawtooth(), 0.3) << "seed " << seed;
    EXPECT_LE(raw.sawtooth(), 0.1) << "seed " << seed;
  }
}

TEST(LaserConicGuidedSearch, AStretchIsFittedAtTheWidthOfItsBrightness)
{
  // The final ellipse's stretches (guided_stretches.cpp) read the brightness R + G + B, whose stripe keeps the
  // luma's full resolution; the width the detector observes is that of the colour's crossings, which JPEG's
  // half-resolution chroma widens. Through quality 60 the faint ring's crossings measured 7 px and its brightness
  // 3-4 px at half maximum: a 7 px stripe over a quadratic background fitted the troughs beside the stripe, and
  // the choice of the fit then took, past a best fit refused as a step, whatever positive fit came last (an
  // amplitude of 0.2 at the edge of the window where the mean profile held a stripe of 6 grey levels). Each
  // stretch is now fitted at the observed width and every narrower one down to 3 px, the least residual taken.
  // Measured: the wide lens's seed 72 (JPEG 90) 99.22 -> 99.95 % of the ring at 3 sigma; seed 60 through JPEG 60
  // 97.89 -> 98.44 %, of what the compression kept 98.44 -> 99.03 %.
  vpLaserConicDetector wideDetector;
  const GuidedQuality wide = runGuided("stretch_width_wide_72", tiltedGround(), fadingRing(40.0, 4.0), 72u,
                                       wideDetector, nullptr, Ridges::skip, wideCamera());
  EXPECT_GE(wide.coverage3, 0.997);
  EXPECT_GE(wide.precision, 0.98);
  Settings s = fadingRing(40.0, 4.0);
  s.jpegQuality = 60;
  vpLaserConicDetector detector;
  const GuidedQuality jpeg = runGuided("stretch_width_jpeg60_60", tiltedGround(), s, 60u, detector, nullptr,
                                       Ridges::skip, camera(), Kept::measure);
  EXPECT_GE(jpeg.coverage3, 0.982);
  EXPECT_GE(jpeg.kept3, 0.987);
  EXPECT_GE(jpeg.precision, 0.98);
}

TEST(LaserConicGuidedSearch, ADarkBoxOverTheDimSideAddsNoPointAlongItsEdge)
{
  // The faint ring through JPEG 60 with a dark box over its dimmest stretch, the box's top edge 3 px above the
  // ring there (the ring runs hidden beside the edge, as in the hard sequence's occluded frames). Points more
  // than 2 px inside the box are off the ring. Measured: seeds 72, 60, 65, 61: no point, precision 0.986,
  // 0.982, 0.987, 0.987 (seed 72: 1 point and 0.977 until the short pieces that stand alone were dropped,
  // RidgeTuning::guidedIsolatedRun: 15 points 1.5-2 px off the ring where it is at 1.6 sigma). Before: the walk into the final ellipse's long gaps on the brightness, let go
  // farther than four samples without a point before it had found one (RidgeTuning::guidedWalkGap), took the
  // JPEG ringing of the box's edge on seed 72 (54 points, precision 0.949), and the brightness measured at the
  // prediction where it crosses a colour edge took it on the other three (27, 30, 57 points 2.7-4 px off the
  // ring, precision 0.954-0.967) until its bump had to stand half the edge's step (RidgeTuning::guidedEdgeBump).
  for (unsigned int seed : {72u, 60u, 65u, 61u}) {
    Settings s = fadingRing(40.0, 4.0);
    s.jpegQuality = 60;
    vpLaserConicSimulator sim = makeSimulator(tiltedGround(), seed);
    const std::vector<vpLaserConicSimulator::vpTraceTruth> truth = sim.traceTruth(6000, s);
    const auto dimmest = std::min_element(truth.begin(), truth.end(), [](const auto &a, const auto &b) {
      return a.peakOverNoise < b.peakOverNoise;
    });
    const vpImagePoint p = dimmest->point;
    const double top = p.get_v() - 3.0, bottom = p.get_v() + 80.0, left = p.get_u() - 60.0, right = p.get_u() + 60.0;
    s.occluders.push_back(
        {vpImagePoint(top, left), vpImagePoint(top, right), vpImagePoint(bottom, right), vpImagePoint(bottom, left)});
    vpLaserConicDetector detector;
    std::vector<vpImagePoint> points;
    const GuidedQuality q =
        runGuided("box_over_the_dim_side_" + std::to_string(seed), tiltedGround(), s, seed, detector, &points);
    const auto inside = std::count_if(points.begin(), points.end(), [&](const vpImagePoint &x) {
      return x.get_u() > left + 2.0 && x.get_u() < right - 2.0 && x.get_v() > top + 2.0 && x.get_v() < bottom - 2.0;
    });
    std::cout << "points more than 2 px inside the box: " << inside << std::endl;
    EXPECT_LE(inside, 2) << "seed " << seed;
    EXPECT_GE(q.precision, 0.98) << "seed " << seed;
  }
}

TEST(LaserConicGuidedSearch, AFaintRingIsNotLocatedOnAFlatEllipseThroughAShortArc)
{
  // The faint ring through the wide lens and JPEG 60: the compression breaks its near side into pieces shorter
  // than the minimum segment but for 25 degrees of arc at its top, nearly straight, to which the first search
  // fitted an ellipse with semi-axes of 70 and 0.8 px; running along that arc on both of its long sides, it
  // was covered at 0.97 by the arc's own points and trusted, so the retry with shorter chains, which locates
  // the ring, did not run: 9.5-15.3 % of the ring at 3 sigma on seeds 60, 61, 62 and 65 (161-379 points).
  // An ellipse flatter than RidgeTuning::traceMinAxisRatio no longer locates a trace: 87.7-95.2 % now
  // (precision >= 0.992; seed 62 at 88.7 % before the short pieces that stand alone were dropped,
  // RidgeTuning::guidedIsolatedRun).
  Settings s = fadingRing(40.0, 4.0);
  s.jpegQuality = 60;
  overSeeds(
      "faint_wide_jpeg60", s, {60u, 61u, 62u, 65u},
      [](unsigned int, const GuidedQuality &q) {
        EXPECT_GE(q.coverage3, 0.85);
        EXPECT_GE(q.precision, 0.98);
      },
      Ridges::skip, wideCamera());
}

TEST(LaserConicGuidedSearch, TheDimSideThroughJpegHoldsItsLineToAFewTenths)
{
  // What the faint rings above hold where the stripe is 2-3 times the noise, whatever the detector: the red
  // dominance read across the *true* centre line (an alignment no detector has), averaged over 80 px of arc
  // and located by a matched filter. Measured on the ten faint cases (seeds 60, 61, 63, 65, 117, plain and
  // through the wide lens): 0.25-0.62 px RMS through JPEG 90, 0.07-0.15 px uncompressed; over 160 px of arc
  // 0.21-0.45 px. Here seed 61 through the wide lens, where the second pass is 0.33 px RMS
  // (FaintRingThroughAWideDistortedLens), and seed 63: 0.48 and 0.45 px through JPEG 90, 0.11 px each
  // uncompressed. vpLaserConicDetector::setGuidedThresholdFactor() quotes these figures.
  const struct
  {
    unsigned int seed;
    bool wide;
  } cases[] = {{61u, true}, {63u, false}};
  for (const auto &c : cases)
    for (int quality : {90, 0}) {
      Settings s = fadingRing(40.0, 4.0);
      s.jpegQuality = quality;
      vpLaserConicSimulator sim = makeSimulator(tiltedGround(), c.seed);
      sim.setCamera(c.wide ? wideCamera() : camera(), kWidth, kHeight);
      vpImage<vpRGBa> I;
      sim.render(I, s);
      const double rms = trueLineReadingRms(I, sim.traceTruth(6000, s), 80.0, 2.0, 3.0);
      std::cout << "seed " << c.seed << (c.wide ? " (wide lens)" : "") << ", JPEG " << quality
                << ": the true line's reading at 2-3 sigma over 80 px of arc, " << rms << " px RMS" << std::endl;
      if (quality > 0)
        EXPECT_GE(rms, 0.3) << "seed " << c.seed;
      else
        EXPECT_LE(rms, 0.16) << "seed " << c.seed;
    }
}

TEST(LaserConicGuidedSearch, TheFlankOfAStripeBesideThePredictionIsNotItsPoint)
{
  // Seed 113 of the faint ring through the wide lens (held out in DISABLED_SeedsNeverTunedOn): on the far side,
  // where the stripe is at 1.6-1.9 sigma, the ellipse fitted to the distorted trace runs 1.5-2 px inside it. A
  // sample whose red profile found nothing beside a JPEG colour edge was measured on its brightness within 1 px
  // of that prediction, whose best response was at the window's end on the flank of the stripe's bump: 49
  // points 1.1-2.1 px inside the ring, precision 0.964. A point measured at a prediction must now be a peak of
  // the response inside its window (ProfileWindow::peakWithin): measured precision 0.989, 98.86 % of the ring
  // at 3 sigma (as before), second-pass RMS 0.313 px (0.315).
  vpLaserConicDetector detector;
  const GuidedQuality q = runGuided("flank_beside_prediction", tiltedGround(), fadingRing(40.0, 4.0), 113, detector,
                                    nullptr, Ridges::skip, wideCamera());
  EXPECT_GE(q.precision, 0.98);
  EXPECT_GE(q.coverage3, 0.98);
  EXPECT_LE(q.rmsGuided, 0.34);
}

TEST(LaserConicGuidedSearch, FadingRingOnATexturedFloorWithReflectanceScaledLight)
{
  const Settings s = fadingMosaic();
  // The light scaled by the mosaic's red reflectance: dimmer still on its blue and green patches. Measured over
  // seeds 73-82: 96.4-98.7 % of the ring at 3 sigma or more, mean 97.62 % (96.22 % before the final conic was
  // refitted on its inliers and the short gaps it left uncovered measured again at it), precision 0.9988-1,
  // second-pass RMS 0.094-0.180 px (mean 0.137; 0.214 with the regularisation along 40 px of arc). Of the ring at 3
  // sigma not found, about half has no
  // point within 3 px: the stripe dimmed by the dark joints' reflectance under the threshold, or running
  // inside or along a joint (a ridge within a valley as wide, or a shoulder on a tile's step, which no
  // background box sees as a peak); the rest has a point 1.5-3 px off. JPEG is the limit there: the chroma,
  // at half resolution, smears the stripe and a step of the floor's red together (without sensor noise the
  // compressed image's red-dominance peak lies 1-2 px from the uncompressed one along such a step; rendered
  // without JPEG, seed 80 misses 1.5 % of its ring at 3 sigma instead of 4.8 %). What was tried on this floor
  // and dropped: CHANGELOG.md.
  // Every seed is held to the bounds, the mean coverage to the measured one with a margin.
  // Of the ring seen as a ridge of the image (ridgeCoverage(): 96-98 % of the ring at 3 sigma here, the rest
  // a stripe inside a joint beside a brighter tile, a step): 97.28-99.03 %, mean 98.59 %.
  // Seeds 73-75 under the sanitizers (their means: 97.74 %, ridge 98.59 %, RMS 0.137 px).
  const unsigned int count = static_cast<unsigned int>(laser_test::trials(10, 3));
  const SeedMeans means = overSeeds(
      "fading_mosaic", s, seedRange(73, count),
      [](unsigned int, const GuidedQuality &q) { expectGuided(q, 0.95, 0.3); }, Ridges::measure);
  std::cout << "seeds 73-" << 72 + count << ": mean coverage " << 100.0 * means.coverage3 << " % (seen as a ridge "
            << 100.0 * means.ridge3 << " %)" << std::endl;
  EXPECT_GE(means.coverage3, 0.97);
  EXPECT_GE(means.ridge3, 0.975);
  EXPECT_LE(means.rmsGuided, 0.17);
}

// The same floor and seeds without the JPEG step: what the compression costs. The red dominance
// R - max(G, B) is a difference of colour channels, which JPEG keeps at half resolution and quantises more
// coarsely than the brightness. Measured: 97.9-99.9 % of the ring at 3 sigma on every seed, mean 99.07 %
// (97.62 % with JPEG 90), precision 0.9996-1, second-pass RMS 0.035-0.055 px, mean 0.045 (0.137 with JPEG).
// Every seed meets the bounds here; the means' bounds are the measured ones with a margin, so that a
// change that loses ring or precision on this floor fails here too. Seeds 73-75 under the sanitizers.
TEST(LaserConicGuidedSearch, FadingMosaicWithoutJpegMeetsTheBoundsOnEverySeed)
{
  Settings s = fadingMosaic();
  s.jpegQuality = 0;
  const SeedMeans means = overSeeds("fading_mosaic_no_jpeg", s,
                                    seedRange(73, static_cast<unsigned int>(laser_test::trials(10, 3))),
                                    [](unsigned int, const GuidedQuality &q) { expectGuided(q, 0.95, 0.3); });
  EXPECT_GE(means.coverage3, 0.985);
  EXPECT_LE(means.rmsGuided, 0.07);
}

TEST(LaserConicGuidedSearch, AStripeLostOnAJointIsFollowedBackFromWhereItIsFoundAgain)
{
  // The textured floor above, seed 76: the walk loses the dim stripe where it crosses a dark joint and finds it
  // again a few samples on, with the whole margin's profiles; the samples in between were left missed, the
  // walk going one way only. Two such stretches, about 20 px of ring each, beside the joints near (777, 989)
  // and (470, 852). Measured: 88 % and 78 % of the ring within 12 px of them found (31 % and 42 % before
  // the backward follow), the whole ring 95.66 % (94.60 %), precision 0.999, second-pass RMS 0.251 px; with the
  // final conic's remeasure 100 % and 94 %, the whole ring 97.86 %, RMS 0.240 px (0.180 px with the
  // regularisation along 80 px of arc).
  std::vector<double> near;
  const GuidedQuality q =
      mosaicNear("joint_backwards", 76, {{vpImagePoint(989.0, 777.0), 12.0}, {vpImagePoint(852.0, 470.0), 12.0}}, near);
  for (double found : near)
    EXPECT_GE(found, 0.7);
  expectGuided(q, 0.95, 0.3);
}

TEST(LaserConicGuidedSearch, AStripeWhoseColourJpegSmearedIsFollowedOnItsBrightness)
{
  // The textured floor above, seed 80: a stripe at about 4 sigma crosses a joint near (515, 893) and is lost
  // for about 15 px on each side of it. Rendered without JPEG it is found there; JPEG stores the colour at
  // half resolution and coarser than the brightness, and beside the joint's edges the stripe's red dominance
  // is smeared into a plateau several pixels wide (a profile across it: 28 grey levels from -2 to +2 px, 25
  // to +6 px, 21-23 beyond), while its brightness, R + G + B, keeps a bump 3 px wide. Measured: 77.7 % of the
  // ring within 20 px of that point found (37.2 % before a follow that the red score lost was searched on the
  // brightness), the whole ring 94.59 % (93.55 %), precision 1, second-pass RMS 0.236 px (0.246); with the
  // final conic's remeasure 100 % and 96.36 % (RMS 0.148 px with the regularisation along 80 px of arc).
  std::vector<double> near;
  const GuidedQuality q = mosaicNear("jpeg_brightness", 80, {{vpImagePoint(893.0, 515.0), 20.0}}, near);
  EXPECT_GE(near[0], 0.7);
  expectGuided(q, 0.94, 0.3);
}

TEST(LaserConicGuidedSearch, AStripeAlongAColourEdgeIsFoundOnItsBrightnessAtThePrediction)
{
  // The textured floor above, seed 73: near (1058, 906) the dim stripe (3.4 sigma) runs on a dark red patch
  // close to its edge, where JPEG's half-resolution chroma leaves its red dominance a plateau that no profile
  // finds, and no point before it to follow. Where the prediction crosses such a colour edge, the brightness
  // within 1 px of the prediction is searched (RidgeTuning::guidedColourEdge). Measured: 90.0 % of the ring within 10 px of that point found (35.0 % before), the whole ring 96.22 %
  // (95.73 %), precision 1, second-pass RMS 0.222 px (0.233); with the final conic's remeasure 100 % and
  // 97.65 % (RMS 0.141 px with the regularisation along 80 px of arc).
  std::vector<double> near;
  const GuidedQuality q = mosaicNear("colour_edge", 73, {{vpImagePoint(906.0, 1058.0), 10.0}}, near);
  EXPECT_GE(near[0], 0.7);
  expectGuided(q, 0.95, 0.3);
}

TEST(LaserConicGuidedSearch, PiecesOfCurveEndOnTheRing)
{
  // The textured floor above over twenty other seeds (83-102), which its bounds were not set on. The worst,
  // seed 93, has its ring along patch joints for stretches, broken into short pieces, and the straight-line
  // regularisation extrapolated at their ends, 2-3 px off the centre line: precision 0.9715. With the mean of
  // the offsets at the ends (RidgeTuning::guidedSmoothEnd): 0.9875. Measured over the twenty: mean 97.22 % of
  // the ring at 3 sigma (94.3 % before the brightness follow, 94.97 % before the brightness at the prediction,
  // 95.34 % before the remeasure where points were dropped, 95.78 % before the final conic was refitted on its
  // inliers and the short gaps it left uncovered measured again), every seed >= 95 % but seed 93, precision
  // 0.990-1, RMS 0.12-0.36 px, mean 0.20 px; with the regularisation along 80 px of arc instead of 40, mean
  // 97.37 %, precision 0.9987-1, RMS 0.062-0.258 px, mean 0.134 px. Short of the bounds on seed 93:
  // 94.25 % of the ring at 3 sigma (93.0 % along 40 px, 86.6 % before the final conic's refit), RMS 0.258 px
  // (0.356, 0.420): about 100 px of its ring run inside a joint beside an orange tile, where the
  // stripe's red fills the joint's dip in red dominance and the profile is a step, not a peak (see
  // TheFinalConicIsTheRingsNotThatOfAWalkBesideIt); the points found there lie 1-1.5 px off, on the tile's
  // edge (the chroma's pull beside a step of the floor's red). Over the ring seen as a ridge of the image
  // (vpLaserConicSimulator::ridgeCoverage(): the stripe also 3 sigma above the scene on both sides, 96-99 % of
  // the ring at 3 sigma here), every seed meets the 95 %: 96.77-99.51 %, mean 98.43 %.
  // Seeds 83-85 under the sanitizers (their means: 97.29 %, ridge 98.31 %, RMS 0.132 px).
  const unsigned int count = static_cast<unsigned int>(laser_test::trials(20, 3));
  const SeedMeans means = overSeeds(
      "fading_mosaic", fadingMosaic(), seedRange(83, count),
      [](unsigned int seed, const GuidedQuality &q) {
        EXPECT_GE(q.precision, 0.98) << "seed " << seed;
        EXPECT_GE(q.coverage3, 0.92) << "seed " << seed;
        EXPECT_GE(q.ridge3, 0.95) << "seed " << seed;
        EXPECT_LE(q.rmsGuided, 0.3) << "seed " << seed;
      },
      Ridges::measure);
  std::cout << "seeds 83-" << 82 + count << ": mean coverage " << 100.0 * means.coverage3 << " % (seen as a ridge "
            << 100.0 * means.ridge3 << " %), mean second-pass RMS " << means.rmsGuided << " px" << std::endl;
  EXPECT_GE(means.coverage3, 0.965);
  EXPECT_GE(means.ridge3, 0.975);
  EXPECT_LE(means.rmsGuided, 0.17);
}

// A study of seeds that no setting was measured on: thirty more seeds of the mosaic (103-132) and twenty of the
// faint ring (100-119), looked at once the final-ellipse step was in place (disabled: about 70 s; run with
// --gtest_also_run_disabled_tests --gtest_filter='*NeverTunedOn*'). Measured: mosaic mean 97.21 % of the ring
// at 3 sigma, every seed >= 94.58 % (seed 124, the ring inside a joint, as seed 93's), precision >= 0.978;
// faint ring mean 99.55 %, every seed >= 98.91 %, precision >= 0.989 (the code before the step, f126958:
// mosaic 95.99 %, five seeds under 95 %; faint 99.38 %). The bounds leave a margin under the measured. Of the
// mosaic's ring seen as a ridge of the image (ridgeCoverage()): mean 98.22 %, every seed >= 95.33 % (seed 124).
// With the regularisation along 80 px of arc instead of 40: mosaic mean 97.52 %, every seed >= 95.91 % (seed
// 124 96.82 %), precision >= 0.9979, second-pass RMS mean 0.146 px, at most 0.239 px (0.210, 0.318 along 40);
// faint ring RMS mean 0.201 px, at most 0.328 px (seed 117; 0.252, 0.360 along 40), two seeds above 0.3 px.
// The faint ring through the wide distorted lens (FaintRingThroughAWideDistortedLens), seeds 100-119: mean
// 98.98 % of the ring at 3 sigma, every seed >= 96.93 %; second-pass RMS mean 0.219 px, at most 0.344 px (seed
// 117), three seeds above 0.3 px; precision 0.964 on seed 113 and 0.977 on seed 104 (1 or nearly elsewhere):
// points on the far side where the stripe is at 1.6-1.9 sigma, 1.1-2.1 px inside the ring (rendered without
// JPEG, seed 113: precision 1, RMS 0.047 px), see TheFlankOfAStripeBesideThePredictionIsNotItsPoint. Since a
// point measured at a prediction must be a peak inside its window (ProfileWindow::peakWithin): through the
// wide lens 99.02 %, every seed >= 97.08 %, precision >= 0.988, RMS mean 0.222 px, at most 0.339 px (seed
// 117), four seeds above 0.3 px; faint ring 99.44 %, every seed >= 98.15 %, precision >= 0.986, RMS mean
// 0.196 px, at most 0.311 px (seed 117), one seed above 0.3 px; mosaic 97.50 %, every seed >= 95.72 %,
// precision >= 0.9979, RMS mean 0.147 px, at most 0.236 px. Since a long gap is followed on the brightness
// (walkIntoLongGaps()): through the wide lens 99.18 %, every seed >= 97.61 %, precision >= 0.988, RMS mean
// 0.222 px, at most 0.353 px (seed 117), two seeds above 0.3 px; faint ring 99.47 %, every seed >= 98.59 %,
// precision >= 0.986, RMS mean 0.197 px, at most 0.310 px (seed 117), one seed above 0.3 px; mosaic 97.58 %,
// every seed >= 95.97 %, precision >= 0.9954, RMS mean 0.149 px, at most 0.238 px. Since the short pieces that
// stand alone are dropped (RidgeTuning::guidedIsolatedRun): through the wide lens 99.19 %, every seed >=
// 97.61 %, precision >= 0.992, RMS mean 0.206 px, at most 0.344 px (seed 117), one seed above 0.3 px; faint
// ring 99.46 %, every seed >= 98.59 %, precision >= 0.986, RMS mean 0.183 px, at most 0.287 px; mosaic as
// before. The final ellipse measured stretch by stretch (guided_stretches.cpp) left this study as it was with a
// straight background under the stretches' stripe; with the quadratic one: through the wide lens 99.39 %,
// every seed >= 98.05 %, precision >= 0.9905, RMS mean 0.218 px, at most 0.341 px (seed 117); faint ring
// 99.65 %, every seed >= 98.74 %, precision >= 0.989, RMS mean 0.206 px, at most 0.334 px (seed 104, 0.268 px
// before: the points the stretches fill or move where its stripe is at 1.6-2.3 sigma lie 1.0-1.7 px from the
// line, and a straight background's fit of the same stretches agrees with them within 1 px); mosaic 97.65 %,
// every seed >= 96.08 %, precision >= 0.9954, RMS mean 0.151 px, at most 0.237 px. Since a stretch fills or
// moves only when it stands out of one pixel's noise (AStretchBarelyOutOfThePixelsNoiseNeitherFillsNorMoves):
// through the wide lens 99.36 %, every seed >= 98.05 %, precision >= 0.992, RMS mean 0.208 px, at most 0.344 px
// (seed 117); faint ring 99.63 %, every seed >= 98.74 %, precision >= 0.986, RMS mean 0.186 px, at most 0.287 px
// (seed 117); mosaic 97.63 %, every seed >= 96.00 %, precision >= 0.9954, RMS mean 0.150 px, at most 0.238 px.
TEST(LaserConicGuidedSearch, DISABLED_SeedsNeverTunedOn)
{
  const SeedMeans mosaic = overSeeds(
      "fading_mosaic", fadingMosaic(), seedRange(103, 30),
      [](unsigned int seed, const GuidedQuality &q) {
        EXPECT_GE(q.coverage3, 0.94) << "seed " << seed;
        EXPECT_GE(q.ridge3, 0.95) << "seed " << seed;
        EXPECT_GE(q.precision, 0.975) << "seed " << seed;
      },
      Ridges::measure);
  const SeedMeans faint =
      overSeeds("faint", fadingRing(40.0, 4.0), seedRange(100, 20), [](unsigned int seed, const GuidedQuality &q) {
        EXPECT_GE(q.coverage3, 0.98) << "seed " << seed;
        EXPECT_GE(q.precision, 0.985) << "seed " << seed;
      });
  const SeedMeans faintWide = overSeeds(
      "faint_wide", fadingRing(40.0, 4.0), seedRange(100, 20),
      [](unsigned int seed, const GuidedQuality &q) {
        EXPECT_GE(q.coverage3, 0.96) << "seed " << seed;
        EXPECT_GE(q.precision, 0.98) << "seed " << seed;
      },
      Ridges::skip, wideCamera());
  std::cout << "mosaic seeds 103-132: mean coverage " << 100.0 * mosaic.coverage3 << " % (seen as a ridge "
            << 100.0 * mosaic.ridge3 << " %), mean second-pass RMS " << mosaic.rmsGuided
            << " px; faint seeds 100-119: " << 100.0 * faint.coverage3 << " %, mean second-pass RMS " << faint.rmsGuided
            << " px; through the wide lens: " << 100.0 * faintWide.coverage3 << " %, mean second-pass RMS "
            << faintWide.rmsGuided << " px" << std::endl;
  EXPECT_GE(mosaic.coverage3, 0.965);
  EXPECT_GE(faint.coverage3, 0.99);
  EXPECT_GE(faintWide.coverage3, 0.98);
}

TEST(LaserConicGuidedSearch, TheFinalConicIsTheRingsNotThatOfAWalkBesideIt)
{
  // The textured floor above, seed 93 (one of the twenty held out): for about 100 px around (515, 203) the ring
  // runs inside a joint beside an orange tile, where its red fills the joint's dip in red dominance and the
  // profile is a step; the walk follows the tile's edge 3-5 px off. The least-squares conic of all the points
  // was pulled by that run (and by shorter ones) to 2.1 px off the true centre line on the far side of the ring
  // (around (830, 987)), where the points it then dropped as off the final curve were on the ring. The final
  // conic is now refitted on the points within 2.5 px of it (refitOnItsInliers(): 0.17 px off at its worst),
  // and the samples of short gaps that no point covers are measured once more at it. Measured: 93.0 % of the ring at 3 sigma,
  // precision 0.991, second-pass RMS 0.356 px, near (830, 987) 96.8 %, along the joint 27.5 % (before: 86.6 %,
  // 0.985, 0.420 px, 58.3 %, 24.0 %); with the regularisation along 80 px of arc instead of 40: 94.25 %, 1,
  // 0.258 px, 96.8 %, 45.4 %. The bounds are not met on this seed (see PiecesOfCurveEndOnTheRing)
  // but on the ring seen as a ridge of the image: 96.52 % (4.1 % of the ring at 3 sigma is a step, not a ridge,
  // most of it along that joint).
  std::vector<double> near; // the far side, and the joint (printed)
  const GuidedQuality q = mosaicNear("ring_in_a_joint", 93,
                                     {{vpImagePoint(987.0, 830.0), 40.0}, {vpImagePoint(203.0, 515.0), 50.0}}, near,
                                     Ridges::measure);
  EXPECT_GE(near[0], 0.95);
  EXPECT_GE(q.coverage3, 0.92);
  EXPECT_GE(q.ridge3, 0.95);
  EXPECT_GE(q.precision, 0.98);
  EXPECT_LE(q.rmsGuided, 0.38);
}

TEST(LaserConicGuidedSearch, SaturatedStripeThroughALampsGlare)
{
  // A laser bright enough to saturate (a white core, red flanks and a red bloom) on glossy white tiles, and the
  // lamp placed so that its reflection lies on the ring: there the floor's red is in the detector's saturation
  // ramp, the profile's values swing with it (several times the dominance's noise) and the flanks were read
  // against that noise: the white core was refused there (measured 9.0 % of the ring within 80 px of the
  // reflection found, 94.95 % of the whole ring; data/laser_hard frames 1, 16 and 31 lost 4-10 % of their
  // rings). The flanks are now read against the dominance's own noise where they fail the profile's: 98.8 %
  // in the glare, 99.93 % of the ring, precision 1, second-pass RMS 0.11 px (0.09 px with the regularisation
  // along 80 px of arc; with a stripe box one pixel
  // wider than the saturated core's even run: 99.1 %, 99.95 %, 0.08 px).
  Settings s;
  s.floor = vpLaserConicSimulator::FLOOR_WHITE_TILES;
  s.ambient = 0.85;
  s.specular = 45.0; // the reflection stays below the sensor's white: the stripe is seen in it
  s.shininess = 250.0;
  s.laserPower = 650.0;
  s.whiteCore = 0.6;
  s.bloom = 0.05;
  s.bloomWidth = 9.0;
  s.stripeWidth = 2.5;
  s.noise = 2.5;
  s.jpegQuality = 80;
  const vpHomogeneousMatrix cMg = tiltedGround();
  const unsigned int seed = 76;
  // The lamp (2.5 m above the ground) at the mirror image of the camera centre through a ring point.
  vpLaserConicSimulator sim = makeSimulator(cMg, seed);
  const vpImagePoint glare = sim.traceTruth(8, s)[1].point;
  double g[2];
  groundPointOf(camera(), cMg, glare, g);
  const vpHomogeneousMatrix gMc = cMg.inverse();
  const double height = std::fabs(gMc[2][3]);
  s.lampX = g[0] + (g[0] - gMc[0][3]) * s.lampZ / height;
  s.lampY = g[1] + (g[1] - gMc[1][3]) * s.lampZ / height;
  vpLaserConicDetector detector;
  std::vector<vpImagePoint> points;
  const GuidedQuality q = runGuided("saturated_glare", cMg, s, seed, detector, &points);
  expectGuided(q, 0.95, 0.3);
  // The ring within 80 px of the reflection's centre.
  std::vector<vpLaserConicSimulator::vpTraceTruth> inGlare;
  for (const vpLaserConicSimulator::vpTraceTruth &t : sim.traceTruth(6000, s))
    if (vpImagePoint::distance(t.point, glare) < 80.0)
      inGlare.push_back(t);
  const double glareCoverage = vpLaserConicSimulator::stripeCoverage(inGlare, points, 3.0, 1.5);
  std::cout << "in the glare: " << 100 * glareCoverage << " % of the ring" << std::endl;
  EXPECT_GE(glareCoverage, 0.95);
}

TEST(LaserConicGuidedSearch, DistractorsStayOut)
{
  // A red disc, a red square and a thin red cable over a fading ring: the second pass adds only points of
  // the ring (the first pass alone keeps the cable; the sample of rows' crossings on it are off the located
  // ellipse and not returned).
  Settings s = fadingRing(150.0, 20.0);
  typedef vpLaserConicSimulator::vpDistractor Distractor;
  s.distractors = {Distractor::disc(0.25, 0.05, 0.15), Distractor::square(-0.05, -0.22, 0.06),
                   Distractor::line(-0.3, 0.2, 0.1, 0.3, 0.004)};
  s.clutter = 80;
  s.clutterRadius = 0.5;
  // Measured: 99.7 % of the ring at 3 sigma (98.8 % before the final conic's remeasure; the first pass alone
  // 78.3 %), none of the second pass's points off the line, second-pass RMS 0.11 px (0.06 px with the regularisation
  // along 80 px of arc), precision 1 (the first pass alone 0.816, the full
  // search and the second pass 0.845: the cable's points were the first pass's).
  vpLaserConicDetector detector, firstPass;
  firstPass.setGuidedSearch(false);
  const GuidedQuality q = runGuided("fading_distractors", tiltedGround(), s, 74, detector);
  const GuidedQuality first = runGuided("fading_distractors_first_pass", tiltedGround(), s, 74, firstPass);
  EXPECT_GE(q.coverage3, 0.95);
  EXPECT_GT(q.coverage3, first.coverage3 + 0.05);
  EXPECT_LE(q.guidedOff, 0.02);
  EXPECT_GE(q.precision, 0.98);
  EXPECT_LE(q.rmsGuided, 0.3);
}

namespace
{
/*!
  A red cable laid on the ground along the dim side of the ring of \e s on \e cMg: a straight line tangent to
  the ring at its dimmest visible point, moved outwards so that its centre line is \e gapPx pixels from the
  stripe's there, \e widthPx pixels wide, as long as \e lengthPx pixels of the ring. \e stretch: the indices of
  the truth samples (traceTruth(6000)) within that length.
*/
vpLaserConicSimulator::vpDistractor cableAlongTheDimSide(const vpHomogeneousMatrix &cMg, const Settings &s,
                                                         double gapPx, double widthPx, double lengthPx,
                                                         std::vector<size_t> &stretch)
{
  vpLaserConicSimulator sim = makeSimulator(cMg);
  const std::vector<vpLaserConicSimulator::vpTraceTruth> truth = sim.traceTruth(6000, s);
  size_t dimmest = 0;
  for (size_t k = 0; k < truth.size(); ++k)
    if (truth[k].peakDominance < truth[dimmest].peakDominance)
      dimmest = k;
  // The truth samples within lengthPx / 2 of arc on each side of the dimmest (consecutive in the list).
  stretch.clear();
  const size_t n = truth.size();
  size_t first = dimmest, last = dimmest;
  for (double arc = 0.0; arc < 0.5 * lengthPx;) {
    const size_t previous = (first + n - 1) % n;
    arc += vpImagePoint::distance(truth[previous].point, truth[first].point);
    first = previous;
  }
  for (double arc = 0.0; arc < 0.5 * lengthPx;) {
    const size_t next = (last + 1) % n;
    arc += vpImagePoint::distance(truth[next].point, truth[last].point);
    last = next;
  }
  for (size_t k = first; k != (last + 1) % n; k = (k + 1) % n)
    stretch.push_back(k);
  const vpCameraParameters cam = camera();
  double a[2], b[2], m[2], centre[2] = {0.0, 0.0};
  groundPointOf(cam, cMg, truth[first].point, a);
  groundPointOf(cam, cMg, truth[last].point, b);
  groundPointOf(cam, cMg, truth[dimmest].point, m);
  for (const vpLaserConicSimulator::vpTraceTruth &t : truth) {
    double g[2];
    groundPointOf(cam, cMg, t.point, g);
    centre[0] += g[0] / n;
    centre[1] += g[1] / n;
  }
  // Metres per pixel along the ring there, and the outward normal of the chord.
  const double metresPerPixel =
      std::hypot(b[0] - a[0], b[1] - a[1]) / vpImagePoint::distance(truth[first].point, truth[last].point);
  double nx = -(b[1] - a[1]), ny = b[0] - a[0];
  const double norm = std::hypot(nx, ny);
  nx /= norm;
  ny /= norm;
  if (nx * (m[0] - centre[0]) + ny * (m[1] - centre[1]) < 0.0) {
    nx = -nx;
    ny = -ny;
  }
  const double offset = gapPx * metresPerPixel, tx = (b[0] - a[0]) * 0.75, ty = (b[1] - a[1]) * 0.75;
  const double cx = m[0] + offset * nx, cy = m[1] + offset * ny;
  return vpLaserConicSimulator::vpDistractor::line(cx - tx, cy - ty, cx + tx, cy + ty, widthPx * metresPerPixel);
}
} // namespace

TEST(LaserConicGuidedSearch, AStripeBesideARedCableIsFound)
{
  // A red cable 8 px wide laid along the dim side of a fading ring (20 grey levels, 10 sigma), its centre line
  // 10, 13 or 14 px from the stripe's where it is closest: the background box on the cable's side reaches its
  // flank. Measured over the 160 px of ring beside it: at 13 px 95.3 % found at 3 sigma (78.5 % when the
  // stripe was read against the brighter of its two sides only, as a step edge is; 90.9 % before the samples
  // whose points were dropped off the final curve were measured again on their brightness, 94.1 % before
  // the short gaps the final conic left uncovered were), at 14 px 97.3 % (89.7 %; 96.2 %), at 10 px, where the
  // stripe and the cable's flank make one slope, 33.6 % (28.0 %; 29.2 %); precision 1.
  const struct
  {
    double gap, minBeside;
  } cases[] = {{10.0, 0.25}, {13.0, 0.92}, {14.0, 0.96}};
  for (const auto &c : cases) {
    Settings s = fadingRing(150.0, 20.0);
    std::vector<size_t> stretch;
    s.distractors = {cableAlongTheDimSide(tiltedGround(), s, c.gap, 8.0, 160.0, stretch)};
    vpLaserConicDetector detector;
    std::vector<vpImagePoint> points;
    const GuidedQuality q = runGuided("cable_beside", tiltedGround(), s, 76, detector, &points);
    vpLaserConicSimulator sim = makeSimulator(tiltedGround(), 76);
    const std::vector<vpLaserConicSimulator::vpTraceTruth> truth = sim.traceTruth(6000, s);
    std::vector<vpLaserConicSimulator::vpTraceTruth> beside;
    beside.reserve(stretch.size());
    for (size_t k : stretch)
      beside.push_back(truth[k]);
    const double besideCoverage = vpLaserConicSimulator::stripeCoverage(beside, points, 3.0, 1.5);
    std::cout << "cable " << c.gap << " px away: " << beside.size() << " samples beside it, coverage "
              << 100.0 * besideCoverage << " %" << std::endl;
    expectGuided(q, 0.95, 0.3);
    EXPECT_GE(besideCoverage, c.minBeside) << "cable " << c.gap << " px away";
  }
}

TEST(LaserConicGuidedSearch, TracksWithThePreviousConic)
{
  // The conic of the previous frame (the exact one of a ground 1 cm higher and 1 deg tilted) as the search
  // region: only profiles along it are read; the fading ring of this frame is found as in the whole image.
  const vpHomogeneousMatrix cMg = tiltedGround();
  const vpHomogeneousMatrix previous = cMg * vpHomogeneousMatrix(0.0, 0.0, 0.01, vpMath::rad(1.0), 0.0, 0.0);
  const vpMatrix Cv = imageConicOf(previous);
  vpLaserConicDetector tracker;
  tracker.setSearchRegion(Cv, 20.0);
  EXPECT_EQ(tracker.getTrackingStep(), 2u);
  // Measured at the default tracking step (a profile every 2nd line): 99.8 % of the ring, precision 1,
  // RMS 0.06 px, 1297 points (the bright side is measured by the guided pass too). At step 1: 100 %, the
  // same RMS, twice the points.
  const GuidedQuality q = runGuided("tracked", cMg, fadingRing(150.0, 15.0), 75, tracker);
  expectGuided(q, 0.95, 0.3);
  EXPECT_EQ(q.guided, q.points); // every point from the guided search
  vpLaserConicDetector everyLine;
  everyLine.setSearchRegion(Cv, 20.0);
  everyLine.setTrackingStep(1);
  const GuidedQuality all = runGuided("tracked_every_line", cMg, fadingRing(150.0, 15.0), 75, everyLine);
  expectGuided(all, 0.95, 0.3);
  EXPECT_NEAR(static_cast<double>(q.points) / all.points, 0.5, 0.05); // one profile in two
  EXPECT_LE(q.rmsGuided, all.rmsGuided + 0.05);                       // as accurate
}

TEST(LaserConicGuidedSearch, APieceThroughTheFirstSampleOfTheRingIsOnePiece)
{
  // The samples of a tracked ring go round it from its leftmost point (their order along the curve starts
  // there), and a piece of curve shorter than RidgeTuning::guidedMinRun with no known point is dropped. Before
  // the pieces were read round the ring, the stretch just below that point, at the end of the samples' list, was
  // one piece and the stretch above it, at their start, another. Here a dark object hides the ring from 150 to
  // 179 degrees (angles about the conic's centre in the image; the leftmost point at 180): the degree between the
  // object and the leftmost point (7 points) was dropped, 0 % of it found, 99.67 % of the ring (measured); now
  // it continues the rest of the ring: 100 % and 100 %.
  const vpHomogeneousMatrix cMg = tiltedGround();
  Settings s = fadingRing(150.0, 100.0);
  const std::vector<vpLaserConicSimulator::vpTraceTruth> ring = makeSimulator(cMg).traceTruth(6000, s);
  // The centre of the image conic, about which the samples are ordered.
  const vpMatrix C = imageConicOf(cMg);
  const double det = C[0][0] * C[1][1] - C[0][1] * C[0][1];
  const vpImagePoint centre((C[0][1] * C[0][2] - C[0][0] * C[1][2]) / det,
                            (C[0][1] * C[1][2] - C[1][1] * C[0][2]) / det);
  double radius = 0.0;
  for (const vpLaserConicSimulator::vpTraceTruth &t : ring)
    radius += vpImagePoint::distance(t.point, centre) / ring.size();
  const auto at = [&](double degrees, double r) {
    return vpImagePoint(centre.get_i() + r * std::sin(vpMath::rad(degrees)),
                        centre.get_j() + r * std::cos(vpMath::rad(degrees)));
  };
  s.occluders.push_back({centre, at(150.0, 2.0 * radius), at(164.5, 2.0 * radius), at(179.0, 2.0 * radius)});
  vpLaserConicDetector tracker;
  tracker.setSearchRegion(C, 20.0);
  std::vector<vpImagePoint> points;
  const GuidedQuality q = runGuided("through_the_first_sample", cMg, s, 79, tracker, &points);
  const std::vector<vpLaserConicSimulator::vpTraceTruth> truth = makeSimulator(cMg, 79).traceTruth(6000, s);
  // The degree between the object and the leftmost point.
  const double between = coverageNear(truth, points, at(179.5, radius), vpMath::rad(0.5) * radius);
  EXPECT_GE(between, 0.9);
  EXPECT_EQ(q.guided, q.points); // tracked: every point from the guided pass
  expectGuided(q, 0.95, 0.3);
}

TEST(LaserConicGuidedSearch, TrackingFollowsTheStripesWidth)
{
  // Climbing, the stripe narrows in the image (the laser's line keeps its width on the ground). The tracker
  // starts on a 7 px stripe detected over the whole image, then follows the ring, now 3 px wide, from frame
  // to frame: its matched filter must follow the width it measures, not keep the first detection's.
  // Measured: RMS 0.039, 0.039, 0.031 px over the three tracked frames, a fresh tracker 0.028 px (0.069,
  // 0.062, 0.056 and 0.051 px with the regularisation along 40 px of arc); keeping the first width, 0.084 px
  // on the third (along 40 px). The width settles at 5, not at the 4 a fresh tracker measures: the
  // half-maximum run is read against the background boxes of the filter in use, farther from a wider box.
  const vpHomogeneousMatrix cMg = tiltedGround();
  Settings wide = fadingRing(150.0, 20.0);
  wide.stripeWidth = 7.0;
  vpLaserConicDetector tracker;
  runGuided("wide_start", cMg, wide, 77, tracker);
  tracker.setSearchRegion(imageConicOf(cMg), 20.0);
  GuidedQuality q;
  for (unsigned int frame = 0; frame < 3; ++frame)
    q = runGuided("narrow_tracked_" + std::to_string(frame), cMg, fadingRing(150.0, 20.0), 78 + frame, tracker);
  vpLaserConicDetector fresh;
  fresh.setSearchRegion(imageConicOf(cMg), 20.0);
  const GuidedQuality reference = runGuided("narrow_fresh", cMg, fadingRing(150.0, 20.0), 80, fresh);
  expectGuided(q, 0.95, 0.3);
  EXPECT_LE(q.rmsGuided, reference.rmsGuided + 0.02);
}

TEST(LaserConicGuidedSearch, TrackingAFrameWithoutTheLaserFindsNoRing)
{
  // Flight: the laser is off in this frame (pulsed laser, dropped exposure) and the tracker searches along
  // the previous frame's conic. Over a colourful mosaic, thin wedges of patch colour between dark joints have
  // a stripe's profile, and pieces of a few of them along the prediction are each long enough to continue a
  // curve (8 profiles): before, 50-80 such points came back as a "tracked" trace, all round the prediction,
  // and GP-3 made a plane of them (data/laser_hard frame 47: 1.4 m and 73 deg off). A track is kept only
  // with a piece of curve as long as the first pass needs to believe in a stripe (setMinSegmentLength());
  // else the first pass searches the band, which finds none of it either.
  const vpHomogeneousMatrix cMg = tiltedGround();
  const vpMatrix Cv = imageConicOf(cMg);
  for (int floor = vpLaserConicSimulator::FLOOR_DARK_TILES; floor <= vpLaserConicSimulator::FLOOR_WHITE_TILES;
       ++floor) {
    for (unsigned int seed = 76; seed < 76 + static_cast<unsigned int>(laser_test::trials(4, 1)); ++seed) {
      Settings s = fadingRing(150.0, 20.0);
      s.floor = static_cast<vpLaserConicSimulator::vpFloorType>(floor);
      s.reflectanceScaled = true;
      s.laserOn = false;
      vpLaserConicSimulator sim = makeSimulator(cMg, seed);
      vpImage<vpRGBa> I;
      sim.render(I, s);
      vpLaserConicDetector tracker;
      tracker.setSearchRegion(Cv, 20.0);
      const std::vector<vpImagePoint> points = tracker.detect(I);
      std::cout << "laser off, floor " << floor << ", seed " << seed << ": " << points.size() << " points ("
                << tracker.getGuidedPointCount() << " of a guided pass)" << std::endl;
      EXPECT_EQ(tracker.getGuidedPointCount(), 0u) << "floor " << floor << ", seed " << seed;
      EXPECT_LT(points.size(), 30u) << "floor " << floor << ", seed " << seed; // a tracked ring gives ~1300
    }
  }
}

TEST(LaserConicGuidedSearch, SettingsAreCheckedAndTheSecondPassCanBeTurnedOff)
{
  vpLaserConicDetector detector;
  EXPECT_TRUE(detector.getGuidedSearch());
  EXPECT_THROW(detector.setGuidedMargin(0.0), vpLaserConicException);
  EXPECT_THROW(detector.setGuidedMargin(std::nan("")), vpLaserConicException);
  // Found by the detector's fuzz target: a margin of 8e146 px was taken, and the guided pass's window on a
  // line overflowed its integers (a read far outside the image).
  EXPECT_THROW(detector.setGuidedMargin(8.18846e146), vpLaserConicException);
  EXPECT_THROW(detector.setGuidedMargin(vpLaserConicDetector::getMaxMargin() * 1.001), vpLaserConicException);
  EXPECT_THROW(detector.setSearchRegion(std::vector<vpImagePoint>{vpImagePoint(10.0, 10.0)}, 1e12),
               vpLaserConicException);
  vpMatrix circle(3, 3); // (u - 80)^2 + (v - 60)^2 = 50^2
  circle[0][0] = circle[1][1] = 1.0;
  circle[0][2] = circle[2][0] = -80.0;
  circle[1][2] = circle[2][1] = -60.0;
  circle[2][2] = 80.0 * 80.0 + 60.0 * 60.0 - 50.0 * 50.0;
  EXPECT_THROW(detector.setSearchRegion(circle, 1e12), vpLaserConicException);
  EXPECT_NO_THROW(detector.setSearchRegion(circle, vpLaserConicDetector::getMaxMargin()));
  EXPECT_THROW(detector.setGuidedStep(0), vpLaserConicException);
  EXPECT_THROW(detector.setTrackingStep(0), vpLaserConicException);
  EXPECT_THROW(detector.setGuidedThresholdFactor(-1.0), vpLaserConicException);
  detector.setGuidedSearch(false);
  const GuidedQuality off = runGuided("first_pass_only", tiltedGround(), fadingRing(150.0, 15.0), 70, detector);
  EXPECT_EQ(off.guided, 0u);
  EXPECT_LT(off.coverage3, 0.95); // what the second pass is for
}

TEST(LaserConicGuidedSearch, TheWidestMarginAllowedStillFindsTheRing)
{
  // The largest margins the setters take: the guided pass's profiles then span whole image lines, and its
  // preference for a stripe near the prediction keeps the ring's points (a test of bounds, not a setting).
  vpLaserConicDetector detector;
  detector.setGuidedMargin(vpLaserConicDetector::getMaxMargin());
  const GuidedQuality wide = runGuided("widest_margin", tiltedGround(), fadingRing(150.0, 15.0), 70, detector);
  EXPECT_GE(wide.coverage3, 0.95);
  EXPECT_GE(wide.precision, 0.98);
}

namespace
{
//! Whether the image point \e p (undistorted camera \e cam) sees the ground \e cMg inside the rectangle
//! [lo, hiX] x [lo, hiY] of ground coordinates.
bool seesRectangle(const vpCameraParameters &cam, const vpHomogeneousMatrix &cMg, const vpImagePoint &p, double lo,
                   double hiX, double hiY)
{
  double g[2];
  groundPointOf(cam, cMg, p, g);
  return g[0] >= lo && g[0] <= hiX && g[1] >= lo && g[1] <= hiY;
}
} // namespace

TEST(LaserConicGuidedSearch, ChessboardViewsWithReflectanceScaledLight)
{
  // Calibration views as a camera sees them: the laser light scaled by the paper's reflectance (a near-white
  // core on the white squares, a dark red stripe on the black ones), a board of 12 x 9 squares of 5 cm at
  // 0.6, 0.8 and 1.0 m tilted by 18 degrees four ways (the views of vsp-make-laser-calibration-images), noise
  // 2, JPEG 90. The share of the trace on the board (half a square inside its edge) that the detector keeps
  // at its defaults, each view.
  const unsigned int squaresX = 12, squaresY = 9;
  const double square = 0.05;
  const vpHomogeneousMatrix centre(0.5 * squaresX * square, 0.5 * squaresY * square, 0, 0, 0, 0);
  unsigned int seed = 80;
  double worst = 1.0;
  // The four tilts at 0.6 m only under the sanitizers.
  for (double d : laser_test::trialsOf<double>({0.6, 0.8, 1.0}, 1))
    for (const std::pair<double, double> &tilt : {std::make_pair(18.0, 0.0), std::make_pair(0.0, 18.0),
                                                  std::make_pair(-18.0, 0.0), std::make_pair(0.0, -18.0)}) {
      const vpHomogeneousMatrix cMg =
          vpHomogeneousMatrix(0.05, 0.0, d, vpMath::rad(tilt.first), vpMath::rad(tilt.second), 0.2) * centre.inverse();
      vpLaserConicSimulator sim = makeSimulator(cMg, seed++);
      sim.setGroundChessboard(squaresX, squaresY, square);
      Settings s;
      s.reflectanceScaled = true;
      s.whiteCore = 0.6;
      s.laserPower = 400.0 * 255.0 / 215.0; // 400 grey levels on the white squares (albedo 215)
      s.noise = 2.0;
      s.jpegQuality = 90;
      vpImage<vpRGBa> I;
      sim.render(I, s);
      dumpIfRequested("chessboard_" + std::to_string(seed - 1), I);
      vpLaserConicDetector detector;
      const std::vector<vpImagePoint> points = detector.detect(I);
      std::vector<vpLaserConicSimulator::vpTraceTruth> onBoard;
      for (const vpLaserConicSimulator::vpTraceTruth &t : sim.traceTruth(6000, s))
        if (seesRectangle(camera(), cMg, t.point, 0.5 * square, (squaresX - 0.5) * square, (squaresY - 0.5) * square))
          onBoard.push_back(t);
      const double kept = vpLaserConicSimulator::stripeCoverage(onBoard, points, 3.0, 1.5);
      std::cout << "board at " << d << " m, tilt (" << tilt.first << ", " << tilt.second << "): " << points.size()
                << " points (" << detector.getGuidedPointCount() << " of the second pass), " << onBoard.size()
                << " truth samples on the board, " << 100 * kept << " % of the trace on the board kept" << std::endl;
      EXPECT_GT(onBoard.size(), 500u); // the ring crosses the board
      // The points off the line (within 1.5 px): those of the second pass, and all against the first pass alone.
      const TraceLine line(sim);
      vpLaserConicDetector firstPass;
      firstPass.setGuidedSearch(false);
      const std::vector<vpImagePoint> firstPoints = firstPass.detect(I);
      const size_t guided = detector.getGuidedPointCount();
      size_t off = 0, guidedOff = 0, firstOff = 0;
      for (size_t k = 0; k < points.size(); ++k) {
        const bool isOff = line.distance(points[k]) > 1.5;
        off += isOff ? 1 : 0;
        guidedOff += isOff && k >= points.size() - guided ? 1 : 0;
      }
      for (const vpImagePoint &p : firstPoints)
        firstOff += line.distance(p) > 1.5 ? 1 : 0;
      const double precision = 1.0 - static_cast<double>(off) / points.size(),
                   firstPrecision = 1.0 - static_cast<double>(firstOff) / firstPoints.size();
      std::cout << "  precision " << precision << " (first pass alone " << firstPrecision << "), second pass "
                << guidedOff << " of " << guided << " off" << std::endl;
      // Measured: the precision of the first pass alone (0.94-0.99: its points at the squares' corners), the
      // second pass 0.2-3.5 % off.
      EXPECT_GE(precision, firstPrecision - 0.005);
      EXPECT_LE(guidedOff, guided / 25);
      worst = std::min(worst, kept);
    }
  // Measured: 99.77-100 % of the trace on the board kept (the issue: >= 90 %), every view. Before the flank
  // test of the second pass took one line's noise as its scale, 77-94 %: the white cores on the white squares
  // (pink flanks of 10-20 grey levels of red) were refused as white light.
  std::cout << "worst view: " << 100 * worst << " %" << std::endl;
  EXPECT_GE(worst, 0.9);
}
