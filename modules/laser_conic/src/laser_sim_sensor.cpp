/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "laser_sim_sensor.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/laser_conic/vpLaserConicException.h>

namespace
{
// Sensor noise needs millions of Gaussian draws per image: a table of the standard normal quantiles at
// (k + 0.5) / 65536, indexed by 16 random bits, samples it exactly up to a 1/65536 quantisation of the
// probabilities, an order of magnitude faster than transforming uniform draws one by one.
const std::vector<float> &normalQuantiles()
{
  static const std::vector<float> table = [] {
    std::vector<float> q(65536);
    for (size_t k = 0; k < q.size(); ++k) {
      // Inverse of the normal CDF (done once): a few bisection steps to bracket, then Newton steps.
      const double p = (k + 0.5) / q.size();
      double lo = -6.0, hi = 6.0;
      for (int it = 0; it < 8; ++it) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
      }
      double x = 0.5 * (lo + hi);
      for (int it = 0; it < 5; ++it)
        x -= (0.5 * std::erfc(-x / std::sqrt(2.0)) - p) / (std::exp(-0.5 * x * x) / std::sqrt(2.0 * M_PI));
      q[k] = static_cast<float>(x);
    }
    return q;
  }();
  return table;
}

// Small fast generator for the per-pixel noise (xorshift64*), seeded from the simulator's generator.
struct FastRandom
{
  explicit FastRandom(uint64_t seed) : state(seed ? seed : 0x9E3779B97F4A7C15ULL) {}
  uint64_t next()
  {
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return state * 0x2545F4914F6CDD1DULL;
  }
  uint64_t state;
};

// Kernel of a linear motion blur of \e length pixels in the direction \e angle: the segment sampled finely,
// splatted bilinearly, normalised to a unit sum.
cv::Mat motionBlurKernel(double length, double angle)
{
  const int half = static_cast<int>(std::ceil(0.5 * length));
  cv::Mat kernel = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32F);
  const int samples = 8 * (2 * half + 1);
  for (int k = 0; k < samples; ++k) {
    const double t = (k + 0.5) / samples - 0.5;
    const double u = half + t * length * std::cos(angle);
    const double v = half + t * length * std::sin(angle);
    const int u0 = static_cast<int>(std::floor(u)), v0 = static_cast<int>(std::floor(v));
    const float fu = static_cast<float>(u - u0), fv = static_cast<float>(v - v0);
    kernel.at<float>(v0, u0) += (1 - fu) * (1 - fv);
    kernel.at<float>(v0, std::min(2 * half, u0 + 1)) += fu * (1 - fv);
    kernel.at<float>(std::min(2 * half, v0 + 1), u0) += (1 - fu) * fv;
    kernel.at<float>(std::min(2 * half, v0 + 1), std::min(2 * half, u0 + 1)) += fu * fv;
  }
  kernel /= cv::sum(kernel)[0];
  return kernel;
}
} // namespace

void vsp::laser_sim_sensor::applyOptics(cv::Mat &image, double blur, double motionLength, double motionAngle)
{
  if (blur > 0.0)
    cv::GaussianBlur(image, image, cv::Size(0, 0), blur);
  if (motionLength >= 1.0)
    cv::filter2D(image, image, -1, motionBlurKernel(motionLength, motionAngle), cv::Point(-1, -1), 0.0,
                 cv::BORDER_REPLICATE);
}

void vsp::laser_sim_sensor::expose(const cv::Mat &image, double noise, uint64_t seed, vpImage<vpRGBa> &I)
{
  const int W = image.cols, H = image.rows;
  I.resize(static_cast<unsigned int>(H), static_cast<unsigned int>(W));
  const std::vector<float> &quantiles = normalQuantiles();
  FastRandom random(seed);
  const float sensorSigma = static_cast<float>(noise);
  for (int i = 0; i < H; ++i) {
    const float *in = image.ptr<float>(i);
    vpRGBa *out = I[static_cast<unsigned int>(i)];
    for (int j = 0; j < W; ++j, in += 3) {
      float c3[3] = {in[0], in[1], in[2]};
      if (sensorSigma > 0.f) {
        const uint64_t bits = random.next(); // 3 x 16 bits: one normal draw per channel
        for (int k = 0; k < 3; ++k)
          c3[k] += sensorSigma * quantiles[(bits >> (16 * k)) & 0xFFFF];
      }
      unsigned char c[3];
      for (int k = 0; k < 3; ++k)
        c[k] = static_cast<unsigned char>(std::min(255.f, std::max(0.f, c3[k])) + 0.5f); // round to nearest
      out[j] = vpRGBa(c[0], c[1], c[2], 255);
    }
  }
}

void vsp::laser_sim_sensor::compressJpeg(vpImage<vpRGBa> &I, int quality)
{
  const int W = static_cast<int>(I.getWidth()), H = static_cast<int>(I.getHeight());
  cv::Mat bgr(H, W, CV_8UC3);
  for (int i = 0; i < H; ++i) {
    const vpRGBa *in = I[static_cast<unsigned int>(i)];
    unsigned char *out = bgr.ptr<unsigned char>(i);
    for (int j = 0; j < W; ++j, out += 3) {
      out[0] = in[j].B;
      out[1] = in[j].G;
      out[2] = in[j].R;
    }
  }
  std::vector<unsigned char> bytes;
  const cv::Mat decoded = cv::imencode(".jpg", bgr, bytes, {cv::IMWRITE_JPEG_QUALITY, quality})
                              ? cv::imdecode(bytes, cv::IMREAD_COLOR)
                              : cv::Mat();
  if (decoded.rows != H || decoded.cols != W || decoded.type() != CV_8UC3)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the JPEG codec failed on the rendered image");
  for (int i = 0; i < H; ++i) {
    const unsigned char *in = decoded.ptr<unsigned char>(i);
    vpRGBa *out = I[static_cast<unsigned int>(i)];
    for (int j = 0; j < W; ++j, in += 3)
      out[j] = vpRGBa(in[2], in[1], in[0], 255);
  }
}
