/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file fuzzLaserDetector.cpp
  \brief libFuzzer target for vpLaserConicDetector: small colour images made from the input (raw pixels, or
  a red ring of fuzzed shape, brightness and width over a fuzzed floor, so that the guided second pass and
  the tracking mode are reached, not only the first pass on noise), fuzzed settings and search regions (a
  trace or a conic, NaN and degenerate ones included), one to three frames in a row as a tracking loop runs
  them. Invalid settings may throw a vpException; anything else (crash, sanitizer report, hang, another
  exception type, a point returned that is not finite or lies outside the image, a mask of another size
  than the image, more second-pass points than points) is a failure.
*/
#include <algorithm>
#include <cmath>

#include <visp3/core/vpMatrix.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>

#include "fuzzInput.h"

namespace
{
// Largest side of a fuzzed image: big enough for a ring the guided pass follows (its 12 px margin and 50 px
// segments), small enough for thousands of inputs a minute.
constexpr int kMaxSide = 192;

//! A pixel value from the input, now and then one of the levels the detector treats apart (0, saturation).
unsigned char consumeLevel(FuzzedDataProvider &fdp)
{
  static const unsigned char levels[] = {0, 1, 128, 240, 249, 250, 254, 255};
  return fdp.ConsumeIntegralInRange<int>(0, 5) == 0 ? levels[fdp.ConsumeIntegralInRange<int>(0, 7)]
                                                    : fdp.ConsumeIntegral<unsigned char>();
}

//! Every pixel straight from the input (the remaining bytes, repeated when they run out).
void fillRaw(FuzzedDataProvider &fdp, vpImage<vpRGBa> &I)
{
  const std::vector<unsigned char> bytes = fdp.ConsumeBytes<unsigned char>(fdp.ConsumeIntegralInRange<size_t>(0, 4096));
  size_t k = 0;
  for (unsigned int i = 0; i < I.getSize(); ++i) {
    vpRGBa &p = I.bitmap[i];
    if (bytes.empty()) {
      p = vpRGBa(0, 0, 0, 255);
      continue;
    }
    p.R = bytes[k++ % bytes.size()];
    p.G = bytes[k++ % bytes.size()];
    p.B = bytes[k++ % bytes.size()];
    p.A = 255;
  }
}

//! A floor of two colours in squares of a fuzzed size, a red ring (an ellipse of fuzzed centre, axes,
//! angle, width and peak) and a little noise from a seeded generator.
void drawRing(FuzzedDataProvider &fdp, vpImage<vpRGBa> &I)
{
  const vpRGBa floorA(consumeLevel(fdp), consumeLevel(fdp), consumeLevel(fdp)),
      floorB(consumeLevel(fdp), consumeLevel(fdp), consumeLevel(fdp));
  const int square = fdp.ConsumeIntegralInRange<int>(1, 64);
  const double W = I.getWidth(), H = I.getHeight();
  const double cu = fdp.ConsumeFloatingPointInRange<double>(-0.5 * W, 1.5 * W),
               cv = fdp.ConsumeFloatingPointInRange<double>(-0.5 * H, 1.5 * H);
  const double a = fdp.ConsumeFloatingPointInRange<double>(0.5, 1.0 + 2.0 * W),
               b = fdp.ConsumeFloatingPointInRange<double>(0.5, 1.0 + 2.0 * H);
  const double angle = fdp.ConsumeFloatingPointInRange<double>(0.0, M_PI), c = std::cos(angle), s = std::sin(angle);
  const double width = fdp.ConsumeFloatingPointInRange<double>(0.3, 15.0);
  const double peak = fdp.ConsumeFloatingPointInRange<double>(0.0, 400.0); // above 255: a saturated core
  const double fade = fdp.ConsumeFloatingPointInRange<double>(0.0, 1.0);   // peak left on the far side
  const int noise = fdp.ConsumeIntegralInRange<int>(0, 20);
  unsigned int state = fdp.ConsumeIntegral<unsigned int>() | 1u;
  for (unsigned int v = 0; v < I.getHeight(); ++v)
    for (unsigned int u = 0; u < I.getWidth(); ++u) {
      const double du = u - cu, dv = v - cv, x = c * du + s * dv, y = -s * du + c * dv;
      // Distance to the ellipse, to first order: (r - 1) times the local scale of the implicit function.
      const double r = std::sqrt((x / a) * (x / a) + (y / b) * (y / b));
      const double scale = std::max(1e-9, std::sqrt((x / (a * a)) * (x / (a * a)) + (y / (b * b)) * (y / (b * b))));
      const double d = r > 0.0 ? (r - 1.0) * r / scale : a;
      const double along = 0.5 * (1.0 + std::atan2(y, x) / M_PI); // 0..1 around the ring
      const double light = peak * (1.0 - (1.0 - fade) * along) * std::exp(-0.5 * d * d / (width * width));
      const vpRGBa &floor = ((static_cast<int>(u) / square + static_cast<int>(v) / square) % 2) ? floorA : floorB;
      state = state * 1664525u + 1013904223u; // a linear congruential generator: seeded by the input
      const int n = noise == 0 ? 0 : static_cast<int>((state >> 16) % (2 * noise + 1)) - noise;
      auto clip = [](double value) { return static_cast<unsigned char>(std::min(255.0, std::max(0.0, value))); };
      I[v][u] = vpRGBa(clip(floor.R + light + n), clip(floor.G + 0.2 * std::max(0.0, light - 255.0) + n),
                       clip(floor.B + 0.2 * std::max(0.0, light - 255.0) + n), 255);
    }
}

//! A search region: points along a fuzzed curve or arbitrary ones, or a conic (often that of a circle near
//! the image, sometimes arbitrary entries), with a fuzzed margin.
void setRegion(FuzzedDataProvider &fdp, vpLaserConicDetector &detector, unsigned int W, unsigned int H)
{
  const double margin = fdp.ConsumeBool() ? vspFuzz::consumeDouble(fdp)
                                          : fdp.ConsumeFloatingPointInRange<double>(0.5, 40.0);
  if (fdp.ConsumeBool()) {
    std::vector<vpImagePoint> trace(fdp.ConsumeIntegralInRange<size_t>(0, 60));
    for (vpImagePoint &p : trace)
      p.set_ij(fdp.ConsumeBool() ? vspFuzz::consumeDouble(fdp) : fdp.ConsumeFloatingPointInRange<double>(0.0, H),
               fdp.ConsumeBool() ? vspFuzz::consumeDouble(fdp) : fdp.ConsumeFloatingPointInRange<double>(0.0, W));
    detector.setSearchRegion(trace, margin);
    return;
  }
  vpMatrix C(3, 3);
  if (fdp.ConsumeBool()) {
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        C[i][j] = C[j][i] = vspFuzz::consumeDouble(fdp);
  } else { // (u - cu)^2 + (v - cv)^2 = r^2
    const double cu = fdp.ConsumeFloatingPointInRange<double>(-0.5 * W, 1.5 * W),
                 cv = fdp.ConsumeFloatingPointInRange<double>(-0.5 * H, 1.5 * H),
                 r = fdp.ConsumeFloatingPointInRange<double>(0.0, 2.0 * std::max(W, H));
    C[0][0] = C[1][1] = 1.0;
    C[0][2] = C[2][0] = -cu;
    C[1][2] = C[2][1] = -cv;
    C[2][2] = cu * cu + cv * cv - r * r;
  }
  detector.setSearchRegion(C, margin);
}

//! Fuzzed settings; each may be refused with a vpException (the detector then keeps its previous value: see
//! vspFuzz::tryApply()).
void configure(FuzzedDataProvider &fdp, vpLaserConicDetector &detector)
{
  if (fdp.ConsumeIntegralInRange<int>(0, 7) == 0)
    detector.setMethod(vpLaserConicDetector::DETECTION_HSV);
  if (fdp.ConsumeBool())
    detector.setGuidedSearch(fdp.ConsumeBool());
  if (fdp.ConsumeBool())
    detector.setInstructionSet(
        static_cast<vpLaserConicDetector::vpInstructionSet>(fdp.ConsumeIntegralInRange<int>(0, 3)));
  vspFuzz::maybeApply(fdp,
                      [&] { detector.setMinSegmentLength(fdp.ConsumeBool() ? 0.0 : vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { detector.setMinContrast(vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { detector.setNoiseFactor(vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { detector.setMaxStripeWidth(fdp.ConsumeIntegralInRange<unsigned int>(0, 120)); });
  vspFuzz::maybeApply(fdp, [&] { detector.setSaturationLevel(fdp.ConsumeIntegralInRange<unsigned int>(100, 260)); });
  vspFuzz::maybeApply(fdp, [&] { detector.setSamplingStep(fdp.ConsumeIntegralInRange<unsigned int>(0, 12)); });
  vspFuzz::maybeApply(fdp, [&] { detector.setGuidedMargin(vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { detector.setGuidedStep(fdp.ConsumeIntegralInRange<unsigned int>(0, 12)); });
  vspFuzz::maybeApply(fdp, [&] { detector.setTrackingStep(fdp.ConsumeIntegralInRange<unsigned int>(0, 12)); });
  vspFuzz::maybeApply(fdp, [&] { detector.setGuidedThresholdFactor(vspFuzz::consumeDouble(fdp)); });
  if (fdp.ConsumeIntegralInRange<int>(0, 3) == 0)
    vspFuzz::tryApply([&] { setRegion(fdp, detector, kMaxSide, kMaxSide); });
}

//! The checks of one detection's output on image I.
void check(const vpLaserConicDetector &detector, const vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points)
{
  for (const vpImagePoint &p : points) {
    if (!std::isfinite(p.get_u()) || !std::isfinite(p.get_v()))
      vspFuzz::fail("detect() returned a point that is not finite");
    if (p.get_u() < -0.5 || p.get_v() < -0.5 || p.get_u() > I.getWidth() - 0.5 || p.get_v() > I.getHeight() - 0.5)
      vspFuzz::fail("detect() returned a point outside the image");
  }
  if (detector.getGuidedPointCount() > points.size())
    vspFuzz::fail("more second-pass points than points");
  const vpImage<unsigned char> &mask = detector.getMask();
  if (mask.getSize() > 0 && (mask.getWidth() != I.getWidth() || mask.getHeight() != I.getHeight()))
    vspFuzz::fail("a mask of another size than the image");
}

void run(FuzzedDataProvider &fdp)
{
  vpLaserConicDetector detector;
  configure(fdp, detector);
  const unsigned int W = fdp.ConsumeIntegralInRange<unsigned int>(0, kMaxSide),
                     H = fdp.ConsumeIntegralInRange<unsigned int>(0, kMaxSide);
  const int frames = fdp.ConsumeIntegralInRange<int>(1, 3);
  for (int f = 0; f < frames; ++f) {
    vpImage<vpRGBa> I(H, W);
    if (fdp.ConsumeIntegralInRange<int>(0, 3) == 0)
      fillRaw(fdp, I);
    else
      drawRing(fdp, I);
    std::vector<vpImagePoint> points;
    try {
      points = detector.detect(I);
    } catch (const vpException &) {
      continue; // refused (an empty image): the next frame is still to be handled
    }
    check(detector, I, points);
    // A tracking loop's next frame: this frame's points (or a fuzzed region) as the search region.
    if (points.size() >= 5 && fdp.ConsumeBool()) {
      try {
        detector.setSearchRegion(points, fdp.ConsumeFloatingPointInRange<double>(1.0, 30.0));
      } catch (const vpException &) {
      }
    } else if (fdp.ConsumeBool()) {
      try {
        setRegion(fdp, detector, W, H);
      } catch (const vpException &) {
      }
    }
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) { return vspFuzz::runInput(data, size, run); }
