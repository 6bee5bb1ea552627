/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// One profile of the guided pass: the signed red dominance along an image line across the predicted
// curve, a matched filter for a stripe of the observed width against a threshold from the noise measured
// along that profile, then the first pass's shape tests and sub-pixel centre around the best response.
#include "guided_detail.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "ridge_profile.h"
#include "ridge_score.h"

namespace vsp::laser_detector
{
namespace
{
// The profile as the first pass's shape tests read a scan line (see ridge_profile.h): the sums of the lines
// from the buffers, the red channel and dominance of the sample's own line from the image (the shape tests
// read them around one candidate only).
struct ProfileView
{
  const ProfileBuffers &b;
  int n;
  const unsigned char *centre; //!< pixel 0 of the profile on the sample's own line
  ptrdiff_t stride;            //!< bytes from a pixel of the profile to the next
  int length() const { return n; }
  int at(int k) const { return b.value[static_cast<size_t>(k)]; }
  int red(int k) const { return centre[k * stride]; }
  int dominance(int k) const
  {
    const unsigned char *p = centre + k * stride;
    return p[0] - std::max(p[1], p[2]);
  }
};

// The value of one pixel in a profile: the score where the red channel is in the saturation ramp (a saturated
// core is a plateau of 255, as in the first pass), the unclipped red dominance elsewhere (the matched filter
// and the noise estimate are then linear in the sensor's noise: a clipped dark floor would hide both). Both
// are computed and one selected, without a branch: which one a pixel takes is unpredictable on a textured floor.
inline int profileValue(const unsigned char *p, int saturation, int rampStart)
{
  const int score = scorePixel(p, saturation), dominance = p[0] - std::max(p[1], p[2]);
  return p[0] >= rampStart ? score : dominance;
}

// Adds the values of \e n pixels from \e first, \e stride bytes apart, to \e value, or writes them there when
// \e overwrite (the first line: no zeroing pass). A row's stride is a compile-time 4: the loop is then
// vectorised.
template <class Stride>
void addLine(const unsigned char *first, Stride stride, int n, int saturation, int rampStart, bool overwrite,
             int *value)
{
  if (overwrite)
    for (int k = 0; k < n; ++k)
      value[k] = profileValue(first + k * static_cast<ptrdiff_t>(stride), saturation, rampStart);
  else
    for (int k = 0; k < n; ++k)
      value[k] += profileValue(first + k * static_cast<ptrdiff_t>(stride), saturation, rampStart);
}

// Adds the brightness R + G + B of \e n pixels from \e first, \e stride bytes apart, to \e value, or writes it
// there when \e overwrite (see ProfileWindow::brightness).
template <class Stride> void addBrightness(const unsigned char *first, Stride stride, int n, bool overwrite, int *value)
{
  for (int k = 0; k < n; ++k) {
    const unsigned char *p = first + k * static_cast<ptrdiff_t>(stride);
    value[k] = (overwrite ? 0 : value[k]) + p[0] + p[1] + p[2];
  }
}

// Sums the values of pixels [start, start + n) of the sample's line and of its \e half neighbours on each side,
// each shifted along the predicted curve, into b.value, and their prefix sums into b.prefix: the profile's
// values, or with \e brightness their brightness. Returns the lines summed (those inside the image), and in
// \e centre the sample's own line's pixel 0.
int readLines(const vpImage<vpRGBa> &I, const GuidedSample &s, int start, int n, int saturation, int half,
              bool brightness, ProfileBuffers &b, const unsigned char *&centre)
{
  // Grown only: the profiles alternate between short and long, and every entry used is written below (a
  // resize to each profile's length filled the new entries with zeros first).
  if (b.value.size() < static_cast<size_t>(n))
    b.value.resize(static_cast<size_t>(n));
  if (b.prefix.size() < static_cast<size_t>(n) + 1)
    b.prefix.resize(static_cast<size_t>(n) + 1);
  const unsigned char *rgba = reinterpret_cast<const unsigned char *>(I.bitmap);
  const ptrdiff_t W = static_cast<ptrdiff_t>(I.getWidth());
  const int lineLength = static_cast<int>(s.alongRow ? I.getWidth() : I.getHeight());
  const int lineCount = static_cast<int>(s.alongRow ? I.getHeight() : I.getWidth());
  const int rampStart = saturation - RidgeTuning::saturationRamp;
  int used = 0;
  int *value = b.value.data();
  for (int j = -half; j <= half; ++j) {
    const int line = s.line + j, from = start + (j == 0 ? 0 : static_cast<int>(std::lround(j * s.slope)));
    if (line < 0 || line >= lineCount || from < 0 || from + n > lineLength)
      continue;
    const unsigned char *first =
        rgba + (s.alongRow ? 4 * (line * W + from) : 4 * (static_cast<ptrdiff_t>(from) * W + line));
    if (j == 0)
      centre = first;
    if (brightness && s.alongRow)
      addBrightness(first, std::integral_constant<ptrdiff_t, 4>(), n, used == 0, value);
    else if (brightness)
      addBrightness(first, 4 * W, n, used == 0, value);
    else if (s.alongRow)
      addLine(first, std::integral_constant<ptrdiff_t, 4>(), n, saturation, rampStart, used == 0, value);
    else
      addLine(first, 4 * W, n, saturation, rampStart, used == 0, value);
    ++used;
  }
  if (used == 0)
    return 0;
  b.prefix[0] = 0;
  for (int k = 0; k < n; ++k)
    b.prefix[k + 1] = b.prefix[k] + value[k];
  return used;
}

// Robust noise of the profile: 1.4826 MAD / sqrt(6) of the second differences of pixels two apart,
// v[k + 2] - 2 v[k] + v[k - 2] (the same spread as the first pass's differences two pixels apart for white
// noise, see ridge_noise.h), at least RidgeTuning::guidedNoiseFloor per line summed. Second differences
// cancel a ramp: on a textured floor the blurred steps between patches (which the matched filter, against
// the larger of its two backgrounds, does not respond to) filled the first differences and raised the
// threshold several times over where the stripe runs beside a patch's edge (the mosaic of
// FadingRingOnATexturedFloorWithReflectanceScaledLight: 93.8 -> 94.9 % of the ring found; the rings on a
// plain floor as before). The differences that touch [skipFirst, skipLast] (the candidate stripe and its
// tails) are left out: a bright stripe's own edges would raise the threshold it is tested against.
double profileNoise(ProfileBuffers &b, int n, int lines, int skipFirst, int skipLast)
{
  const double floor = RidgeTuning::guidedNoiseFloor * std::sqrt(static_cast<double>(lines));
  // The positions before the skipped stretch, then those after it (k + 2 < skipFirst or k - 2 > skipLast):
  // two loops without a test per position.
  b.diffs.resize(static_cast<size_t>(std::max(0, n - 4)));
  size_t count = 0;
  const int *v = b.value.data();
  int k = 2;
  for (; k + 2 < n && k + 2 < skipFirst; ++k)
    b.diffs[count++] = std::abs(v[k + 2] - 2 * v[k] + v[k - 2]);
  for (k = std::max(k, skipLast + 3); k + 2 < n; ++k)
    b.diffs[count++] = std::abs(v[k + 2] - 2 * v[k] + v[k - 2]);
  b.diffs.resize(count);
  if (b.diffs.empty())
    return floor;
  const double mad = middleValue(b.diffs);
  return std::max(floor, 1.4826 * mad / std::sqrt(6.0));
}

// Robust noise of the red dominance along the sample's own line (1.4826 MAD / sqrt(2) of the differences two
// pixels apart), the differences touching [skipFirst, skipLast] left out. Where the red channel is in the
// saturation ramp (a lamp's glare on a white floor) the profile's values swing with the red channel and their
// noise is several times the dominance's: this is the noise a saturated core's red flanks are read against.
double dominanceNoise(const ProfileView &view, std::vector<int> &diffs, int skipFirst, int skipLast)
{
  diffs.clear();
  for (int k = 0; k + 2 < view.n; ++k)
    if (k + 2 < skipFirst || k > skipLast)
      diffs.push_back(std::abs(view.dominance(k + 2) - view.dominance(k)));
  return diffs.empty() ? 0.0 : 1.4826 * middleValue(diffs) / std::sqrt(2.0);
}

// A threshold in the profile's integer units, rounded up (a level beyond an int's range already refuses
// every response).
int thresholdLevel(double level) { return toIntAtMost(std::ceil(level), std::numeric_limits<int>::max()); }

// The matched filter: mean over the stripe box [k - h, k + h] minus the larger mean of the background boxes
// of f pixels beyond a gap on each side (a step edge has one bright side and fails, as in the first pass).
// In integers, scaled by (2h + 1) f, then one multiplication (the divisions of three means per response
// were a good part of a tracked frame's profiles). With \e againstDimmer, the smaller mean instead: a stripe
// followed beside a brighter region (see measureProfile()), whose flank the half-maximum run then keeps out.
struct MatchedFilter
{
  const std::vector<int> &prefix; //!< the profile's prefix sums (the first n + 1 entries)
  int n;                          //!< the profile's pixels
  int h, f;
  double scale;               //!< 1 / ((2h + 1) f): from a scaled response to grey levels
  bool againstDimmer = false; //!< the background is the dimmer box, not the brighter
  MatchedFilter(const std::vector<int> &prefix_, int n_, int h_, int f_)
    : prefix(prefix_), n(n_), h(h_), f(f_), scale(1.0 / ((2.0 * h_ + 1.0) * f_))
  {
  }
  // The positions whose boxes lie inside the profile.
  int lowest() const { return h + RidgeTuning::guidedGap + f; }
  int highest() const { return n - 1 - lowest(); }
  // Pixels on each side of a response's position covered by its stripe box and gap: the stripe and its tails,
  // which a noise estimate beside it leaves out.
  int tails() const { return h + RidgeTuning::guidedGap + 1; }
  // Sums of the left and right background boxes of k.
  int leftSum(int k) const
  {
    return prefix[k - h - RidgeTuning::guidedGap] - prefix[k - h - RidgeTuning::guidedGap - f];
  }
  int rightSum(int k) const
  {
    return prefix[k + h + RidgeTuning::guidedGap + f + 1] - prefix[k + h + RidgeTuning::guidedGap + 1];
  }
  // |left - right| of the background means at k (grey levels of the summed lines), -1 when a box leaves the
  // profile: the step of a colour edge there.
  double backgroundStep(int k) const
  {
    return k < lowest() || k > highest() ? -1.0 : std::abs(leftSum(k) - rightSum(k)) / static_cast<double>(f);
  }
  template <bool Dimmer> int backgroundSum(int k) const
  {
    return Dimmer ? std::min(leftSum(k), rightSum(k)) : std::max(leftSum(k), rightSum(k));
  }
  int backgroundSum(int k) const { return againstDimmer ? backgroundSum<true>(k) : backgroundSum<false>(k); }
  // The background level of k in grey levels, rounded half away from zero as std::lround would round the
  // quotient, in integers (a division and a rounding call per profile in doubles).
  int roundedBackground(int k) const
  {
    const int sum = backgroundSum(k);
    return sum >= 0 ? (2 * sum + f) / (2 * f) : -((f - 2 * sum) / (2 * f));
  }
  // response(k) x (2h + 1) f, exact in integers.
  template <bool Dimmer> long long scaledResponse(int k) const
  {
    const long long stripe = prefix[k + h + 1] - prefix[k - h];
    return stripe * f - static_cast<long long>(backgroundSum<Dimmer>(k)) * (2 * h + 1);
  }
  double response(int k) const
  {
    return static_cast<double>(againstDimmer ? scaledResponse<true>(k) : scaledResponse<false>(k)) * scale;
  }
  // The first k of [first, last] with the largest response (-1 when empty), and that response. (The choice of
  // background is made once per scan: inside the loop it cost a tracked frame 3-4 %.)
  int best(int first, int last, double &bestResponse) const
  {
    return againstDimmer ? best<true>(first, last, bestResponse) : best<false>(first, last, bestResponse);
  }
  template <bool Dimmer> int best(int first, int last, double &bestResponse) const
  {
    int found = -1;
    long long top = 0;
    for (int k = first; k <= last; ++k) {
      const long long r = scaledResponse<Dimmer>(k);
      if (found < 0 || r > top) {
        top = r;
        found = k;
      }
    }
    bestResponse = found < 0 ? -1e30 : static_cast<double>(top) * scale;
    return found;
  }
};

// Where the best response k of the profile (starting at pixel \e start of its line) lies farther than
// RidgeTuning::guidedNearMargin from the prediction: the best response within that margin of it (and within
// the sample's margin and the profile) replaces it when it passes \e threshold (a stripe near the prediction
// is preferred to a stronger one farther off).
void preferNearPrediction(const MatchedFilter &filter, const GuidedSample &s, int start, double threshold, int &k,
                          double &response)
{
  const double predicted = s.pos - start, near = std::min(RidgeTuning::guidedNearMargin / s.toNormal, s.halfWindow);
  const int nearFirst = std::max(filter.lowest(), static_cast<int>(std::floor(predicted - near))),
            nearLast = std::min(filter.highest(), static_cast<int>(std::ceil(predicted + near)));
  if (k >= nearFirst && k <= nearLast)
    return;
  double nearResponse = -1e30;
  const int nearBest = filter.best(nearFirst, nearLast, nearResponse);
  if (nearBest >= 0 && nearResponse >= threshold) {
    k = nearBest;
    response = nearResponse;
  }
}

// The response that the profile of sample s (from pixel \e start of its line) is judged on, given the best one
// (best, bestResponse) of its window [first, last] and the response threshold.
void selectStripe(MatchedFilter &filter, const GuidedSample &s, const ProfileWindow &window, bool drifted, int start,
                  int first, int last, double threshold, int &best, double &bestResponse)
{
  // The whole margin: a response near the prediction that passes the threshold is preferred to a stronger one
  // farther off (see RidgeTuning::guidedNearMargin); the noise stays that measured beside the strongest. A
  // follow likewise once it has drifted from a prediction fitted to the points of the whole image: it had
  // followed a red cable along the ring, step by step (data/laser_hard frame 27: 0.929 -> 0.940 of the ring
  // at 3 sigma), or a patch's edge on the mosaic floor. Not in tracking (ProfileWindow::preferPrediction).
  if (best >= 0 && (window.halfWidth <= 0.0 || drifted))
    preferNearPrediction(filter, s, start, threshold, best, bestResponse);
  if (best >= 0 && bestResponse < threshold && window.halfWidth > 0.0) {
    // A followed stripe whose background box on one side lies on a brighter region (a red cable a few pixels
    // off, a lighter patch): read against the other side. The shape tests then ask for a half-maximum run
    // that ends on both sides, which the flank of a step (no valley between it and the brighter side) fails.
    filter.againstDimmer = true;
    best = filter.best(first, last, bestResponse);
  }
}

// The first pass's shape tests and centre (ridge_profile.h) around the best response k of the profile. A
// saturated core is a laser's when its flanks' red dominance (one line) reaches \e flankThreshold, or, when it
// does not, \e factor times the dominance's own noise along the line (lower than the profile's in a glare).
// The centre only when \e centre is not null (the caller has a better one).
bool shapeAndCentre(const ProfileView &view, const MatchedFilter &filter, int k, const GuidedSettings &settings,
                    int flankThreshold, std::vector<int> &diffs, int &first, int &last, double *centre)
{
  int p = std::max(0, k - filter.h - 1);
  for (int j = p; j <= std::min(view.n - 1, k + filter.h + 1); ++j)
    if (view.at(j) > view.at(p))
      p = j;
  const int bg = filter.roundedBackground(k), contrast = view.at(p) - bg;
  if (contrast <= 0)
    return false;
  const int aboveHalf = bg + contrast / 2, d = settings.maxWidth;
  int a = p, b = p;
  while (a - 1 >= 0 && view.at(a - 1) > aboveHalf && p - a <= d)
    --a;
  while (b + 1 < view.n && view.at(b + 1) > aboveHalf && b - p <= d)
    ++b;
  if (b - a + 1 > settings.maxWidth)
    return false;
  if (whiteWithoutRedFlanks(view, a, b, settings.saturation, flankThreshold)) {
    const int glareThreshold =
        thresholdLevel(std::max(RidgeTuning::guidedMinResponse,
                                settings.factor * dominanceNoise(view, diffs, a - filter.tails(), b + filter.tails())));
    if (glareThreshold >= flankThreshold || whiteWithoutRedFlanks(view, a, b, settings.saturation, glareThreshold))
      return false;
  }
  first = a;
  last = b;
  if (centre != nullptr)
    *centre = stripeCentroid(view, p, a, b, bg, contrast, d);
  return true;
}

// The centre: the vertex of the parabola through the matched filter's responses around its best (the filter
// has averaged the noise; the first pass's centroid of the raw profile, the fallback, is noisier here), in
// \e centre when \e vertex. Its neighbours need their background boxes inside the profile too: [lowest(),
// highest()]. False when \e peakWithin and a neighbour's response is larger (ProfileWindow::peakWithin).
bool responseVertex(const MatchedFilter &filter, int best, double bestResponse, bool peakWithin, double &centre,
                    bool &vertex)
{
  vertex = false;
  if (best - 1 < filter.lowest() || best + 1 > filter.highest())
    return true;
  const double r0 = filter.response(best - 1), r2 = filter.response(best + 1);
  if (peakWithin && (r0 > bestResponse || r2 > bestResponse))
    return false;
  const double curvature = r0 - 2.0 * bestResponse + r2;
  vertex = curvature < 0.0;
  if (vertex)
    centre = best + std::max(-0.5, std::min(0.5, 0.5 * (r0 - r2) / curvature));
  return true;
}

// Half width h of the matched filter's stripe box (2h + 1 pixels). The box is as wide as the observed
// half-maximum run, or a pixel narrower when that is even: a box wider than the stripe flattens the responses
// the centre is read from (a run of 4 pixels, measured on the 3 px stripes of data/laser_sequence, with a box
// of 5: GP-3's roll error 0.028 deg, with a box of 3: 0.024). A faint stripe's profile of many lines keeps the
// pixel more: it sums more of the stripe where finding it is what counts (the faint frame 56 of
// data/laser_hard: 0.949 -> 0.954 of its ring at 3 sigma).
int stripeHalfBox(const GuidedSettings &settings, const ProfileWindow &window)
{
  const int run = window.lines > RidgeTuning::guidedLines ? settings.stripeWidth : settings.stripeWidth - 1;
  return std::max(1, run / 2);
}

constexpr int kCacheLineBytes = 64;

// The cache line holding columns [first, last] of row 0 of an RGBA image W pixels wide, when it holds them in
// every row (a row is a whole number of cache lines, and they do not straddle two), else -1.
long long sharedColumnLine(const unsigned char *rgba, ptrdiff_t W, int first, int last)
{
  const std::uintptr_t line = reinterpret_cast<std::uintptr_t>(rgba + 4 * first) / kCacheLineBytes;
  const bool shared = (4 * W) % kCacheLineBytes == 0 &&
                      reinterpret_cast<std::uintptr_t>(rgba + 4 * last + 3) / kCacheLineBytes == line;
  return shared ? static_cast<long long>(line) : -1;
}

// A hint to bring the cache line of \e p to cache (nothing where the compiler has no such builtin).
inline void prefetch(const unsigned char *p)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}
} // namespace

// By counting when the values are small (the differences of a profile's background mostly are: a few hundred
// nanoseconds of nth_element per profile were a quarter of the tracking mode's time), else by nth_element.
int middleValue(std::vector<int> &values)
{
  constexpr int bins = 128;
  int count[bins] = {0};
  for (int v : values)
    if (v < bins)
      ++count[v];
  const int rank = static_cast<int>(values.size() / 2);
  int below = 0;
  for (int v = 0; v < bins; ++v) {
    below += count[v];
    if (below > rank)
      return v;
  }
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[static_cast<size_t>(rank)];
}

void prefetchProfile(const vpImage<vpRGBa> &I, const GuidedSample &s, int halfWidth, bool oneLine,
                     PrefetchedColumns &last)
{
  const unsigned char *rgba = reinterpret_cast<const unsigned char *>(I.bitmap);
  const ptrdiff_t W = static_cast<ptrdiff_t>(I.getWidth());
  const int lineLength = static_cast<int>(s.alongRow ? I.getWidth() : I.getHeight());
  const int lineCount = static_cast<int>(s.alongRow ? I.getHeight() : I.getWidth());
  const int from = std::max(0, static_cast<int>(s.pos) - halfWidth),
            to = std::min(lineLength - 1, static_cast<int>(s.pos) + halfWidth);
  if (from > to || lineCount < 3)
    return;
  // The sample's line and its two neighbours, or the line alone (see the declaration).
  const int reach = oneLine ? 0 : 1;
  const int line = std::min(lineCount - 1 - reach, std::max(reach, s.line));
  const auto address = [&](int row, int column) { return rgba + 4 * (row * W + column); };
  if (s.alongRow) {
    constexpr int pixelsPerCacheLine = kCacheLineBytes / 4;
    for (int j = -reach; j <= reach; ++j)
      for (int k = from; k < to + pixelsPerCacheLine; k += pixelsPerCacheLine)
        prefetch(address(line + j, std::min(k, to)));
    last.block = -1;
    return;
  }
  // The three columns share a cache line but for one in sixteen: one address a row. The rows the sample
  // before asked for in the same cache line are not asked for again.
  const auto ask = [&](int firstRow, int lastRow) {
    for (int k = firstRow; k <= lastRow; ++k)
      prefetch(address(k, line - reach));
  };
  const long long block = sharedColumnLine(rgba, W, line - reach, line + reach);
  if (block >= 0 && block == last.block) {
    ask(from, std::min(to, last.from - 1));
    ask(std::max(from, last.to + 1), to);
  } else
    ask(from, to);
  last.block = block;
  last.from = from;
  last.to = to;
}

// A profile whose stripe was not found, with the colour edge where the prediction crosses it
// (ProfileResult::edgeAtPrediction; only a profile that finds nothing is asked for it, so that a tracked frame's
// profiles, which find their stripe, do not compute it).
ProfileResult notFound(ProfileResult &result, const MatchedFilter &filter, const GuidedSample &s, int start)
{
  result.edgeAtPrediction = filter.backgroundStep(static_cast<int>(std::lround(s.pos - start)));
  return result;
}

ProfileResult measureProfile(const vpImage<vpRGBa> &I, const GuidedSample &s, const GuidedSettings &settings,
                             const ProfileWindow &window, ProfileBuffers &buffers)
{
  ProfileResult result;
  const int h = stripeHalfBox(settings, window), f = std::max(RidgeTuning::guidedMinFlank, h + 1);
  const int lineLength = static_cast<int>(s.alongRow ? I.getWidth() : I.getHeight());
  const double half = window.halfWidth > 0.0 ? window.halfWidth : s.halfWindow;
  const double from = std::max(s.pos - s.halfWindow, s.pos + window.centre - half),
               to = std::min(s.pos + s.halfWindow, s.pos + window.centre + half);
  const int lo = static_cast<int>(std::floor(from)), hi = static_cast<int>(std::ceil(to));
  const int reach = h + RidgeTuning::guidedGap + f;
  // A follow that has drifted from a prediction fitted to the points of the whole image: the pixels around
  // the prediction are read too (see below).
  const double near = RidgeTuning::guidedNearMargin / s.toNormal;
  const bool drifted = window.halfWidth > 0.0 && window.preferPrediction && std::fabs(window.centre) > near;
  int readLo = drifted ? std::min(lo, static_cast<int>(std::floor(s.pos - near))) : lo,
      readHi = drifted ? std::max(hi, static_cast<int>(std::ceil(s.pos + near))) : hi;
  if (window.brightness) { // the whole margin read, for the brightness's noise (see ProfileWindow::brightness)
    readLo = std::min(readLo, static_cast<int>(std::floor(s.pos - s.halfWindow)));
    readHi = std::max(readHi, static_cast<int>(std::ceil(s.pos + s.halfWindow)));
  }
  const int start = std::max(0, readLo - reach), end = std::min(lineLength - 1, readHi + reach), n = end - start + 1;
  if (hi < lo || n < 2 * reach + 1)
    return result;
  const unsigned char *centreLine = nullptr;
  const int lines =
      readLines(I, s, start, n, settings.saturation, window.lines / 2, window.brightness, buffers, centreLine);
  if (lines == 0 || centreLine == nullptr)
    return result;
  result.lines = lines;
  result.brightness = window.brightness;
  MatchedFilter filter(buffers.prefix, n, h, f);
  double bestResponse = -1e30;
  const int first = std::max(reach, lo - start), last = std::min(n - 1 - reach, hi - start);
  int best = filter.best(first, last, bestResponse);
  const int tails = filter.tails();
  const double rootLines = lines == 1 ? 1.0 : std::sqrt(static_cast<double>(lines));
  if (window.lineNoise >= 0.0)
    result.noise = window.lineNoise * rootLines;
  else
    result.noise = best < 0 ? profileNoise(buffers, n, lines, n, n)
                            : profileNoise(buffers, n, lines, best - tails, best + tails);
  result.threshold =
      std::max(RidgeTuning::guidedMinResponse * lines, settings.factor * result.noise * buffers.filterGain(h, f));
  selectStripe(filter, s, window, drifted, start, first, last, result.threshold, best, bestResponse);
  result.response = bestResponse;
  if (best < 0 || bestResponse < result.threshold)
    return notFound(result, filter, s, start);
  double centre = 0.0;
  bool vertex = false;
  if (!responseVertex(filter, best, bestResponse, window.peakWithin, centre, vertex))
    return notFound(result, filter, s, start);
  int runFirst = 0, runLast = 0;
  // The flanks of a saturated core: red out of one line's noise by the threshold factor. (Half the contrast,
  // in the sum of the lines, refused every white core with pink flanks: the laser on white paper.)
  const int flankThreshold =
      thresholdLevel(std::max(RidgeTuning::guidedMinResponse, settings.factor * result.noise / rootLines));
  if (!shapeAndCentre(ProfileView{buffers, n, centreLine, s.alongRow ? 4 : 4 * static_cast<ptrdiff_t>(I.getWidth())},
                      filter, best, settings, flankThreshold, buffers.diffs, runFirst, runLast,
                      vertex ? nullptr : &centre))
    return notFound(result, filter, s, start);
  const double along = start + centre;
  if (window.brightness) // read by brightnessAtPrediction() only: a tracked frame's profiles do not compute it
    result.stepAtStripe = filter.backgroundStep(best);
  result.found = true;
  result.offset = acrossOf(s, along - s.pos);
  result.crossing.alongRow = s.alongRow;
  result.crossing.line = s.line;
  result.crossing.first = start + runFirst;
  result.crossing.last = start + runLast;
  result.crossing.point = samplePoint(s, along);
  return result;
}
} // namespace vsp::laser_detector
