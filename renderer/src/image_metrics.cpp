#include "renderer/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace renderer {

double Rmse(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  if (a.size() != b.size() || a.empty()) return std::numeric_limits<double>::infinity();
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); i += 4)
    for (int c = 0; c < 3; ++c, ++n) {
      double d = double(a[i + c]) - double(b[i + c]);
      sum += d * d;
    }
  return std::sqrt(sum / double(n));
}

double Psnr(double rmse) {
  return rmse == 0 ? std::numeric_limits<double>::infinity() : 20.0 * std::log10(255.0 / rmse);
}

namespace {

std::vector<double> Luma(const std::vector<uint8_t>& rgba) {
  std::vector<double> y(rgba.size() / 4);
  for (size_t i = 0; i < y.size(); ++i)
    y[i] = 0.299 * rgba[i * 4] + 0.587 * rgba[i * 4 + 1] + 0.114 * rgba[i * 4 + 2];
  return y;
}

std::vector<double> GaussianWindow() {
  std::vector<double> w(size_t(kSsimWindow) * kSsimWindow);
  const int r = kSsimWindow / 2;
  double sum = 0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x)
      sum += w[size_t((y + r) * kSsimWindow + x + r)] = std::exp(-(x * x + y * y) / (2 * kSsimSigma * kSsimSigma));
  for (double& v : w) v /= sum;
  return w;
}

}  // namespace

double Ssim(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, uint32_t width, uint32_t height) {
  if (a.size() != b.size() || a.size() != size_t(width) * height * 4 || width < uint32_t(kSsimWindow) ||
      height < uint32_t(kSsimWindow))
    return std::numeric_limits<double>::quiet_NaN();
  const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  const std::vector<double> x = Luma(a), y = Luma(b), window = GaussianWindow();
  double sum = 0;
  size_t windows = 0;
  for (uint32_t top = 0; top + kSsimWindow <= height; ++top)
    for (uint32_t left = 0; left + kSsimWindow <= width; ++left, ++windows) {
      double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
      for (int j = 0; j < kSsimWindow; ++j)
        for (int i = 0; i < kSsimWindow; ++i) {
          const size_t p = size_t(top + j) * width + left + i;
          const double w = window[size_t(j * kSsimWindow + i)];
          mx += w * x[p], my += w * y[p];
          xx += w * x[p] * x[p], yy += w * y[p] * y[p], xy += w * x[p] * y[p];
        }
      const double vx = xx - mx * mx, vy = yy - my * my, cov = xy - mx * my;
      sum += (2 * mx * my + c1) * (2 * cov + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
    }
  return sum / double(windows);
}

std::vector<uint8_t> PixelError(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  std::vector<uint8_t> error(std::min(a.size(), b.size()) / 4);
  for (size_t i = 0; i < error.size(); ++i)
    for (int c = 0; c < 3; ++c)
      error[i] = uint8_t(std::max(int(error[i]), std::abs(int(a[i * 4 + c]) - int(b[i * 4 + c]))));
  return error;
}

double ShareOff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int steps) {
  const std::vector<uint8_t> error = PixelError(a, b);
  if (error.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto off = std::count_if(error.begin(), error.end(), [&](uint8_t e) { return e > steps; });
  return double(off) / double(error.size());
}

void HeatColour(double steps, int fullScale, uint8_t rgb[3]) {
  // On the square root of the error, so that the few-step errors of the good methods
  // stay visible beside the large ones: black, red, yellow, white in equal thirds.
  const double s = std::sqrt(std::clamp(steps / double(fullScale), 0.0, 1.0)) * 3.0;
  const double channel[3] = {std::clamp(s, 0.0, 1.0), std::clamp(s - 1.0, 0.0, 1.0), std::clamp(s - 2.0, 0.0, 1.0)};
  for (int c = 0; c < 3; ++c) rgb[c] = uint8_t(std::lround(channel[c] * 255.0));
}

std::vector<uint8_t> ErrorHeatMap(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int fullScale) {
  const std::vector<uint8_t> error = PixelError(a, b);
  std::vector<uint8_t> map(error.size() * 4, 255);
  for (size_t i = 0; i < error.size(); ++i) HeatColour(error[i], fullScale, &map[i * 4]);
  return map;
}

}  // namespace renderer
