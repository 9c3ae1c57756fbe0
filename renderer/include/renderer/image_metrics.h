// Distances between two frames of the replays: RGBA8 images in tightly packed rows,
// compared over RGB (alpha ignored) on their stored 8-bit sRGB values, as a viewer
// sees them. One home for these formulas: the comparison (renderer/comparison.h),
// replay --figures and the tests all call them.
#pragma once

#include <cstdint>
#include <vector>

namespace renderer {

// Root mean square of the per-channel differences, in 8-bit steps; infinity when the
// sizes differ or the images are empty.
double Rmse(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);
// Peak signal-to-noise ratio with the peak 255: 20 log10(255 / rmse) dB; infinity when rmse == 0.
double Psnr(double rmse);

// The SSIM window: Gaussian, 11 x 11, sigma 1.5, and the constants K1 = 0.01,
// K2 = 0.03 with L = 255 (Wang, Bovik, Sheikh, Simoncelli 2004).
inline constexpr int kSsimWindow = 11;
inline constexpr double kSsimSigma = 1.5;
// Mean SSIM over every window position that fits inside the image ("valid", as the
// authors' reference code), on the luma of the sRGB values,
// Y' = 0.299 R' + 0.587 G' + 0.114 B' (Rec. 601, no linearisation). 1 for equal
// images; NaN when the sizes differ or the image is smaller than the window.
double Ssim(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, uint32_t width, uint32_t height);

// The share (0..1) of pixels where some channel differs by more than `steps`.
double ShareOff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int steps);

// Per pixel, the largest channel difference in 8-bit steps.
std::vector<uint8_t> PixelError(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);
// An RGBA8 heat map of PixelError: black at 0, through red and yellow to white at
// `fullScale` steps and above (a pixel off by 1 step already shows as dark red).
std::vector<uint8_t> ErrorHeatMap(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int fullScale);
// The colour of an error of `steps` on that map.
void HeatColour(double steps, int fullScale, uint8_t rgb[3]);

}  // namespace renderer
