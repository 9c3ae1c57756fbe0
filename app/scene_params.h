// The demo scene's fixed parameters, shared by app/main.cpp and tests/demo (which
// recomputes a few expected pixels on the CPU from these numbers).
#pragma once

#include <cstdint>

namespace demo {

inline constexpr uint32_t kWidth = 640;
inline constexpr uint32_t kHeight = 360;

// Left-handed world, y up (D3D convention): glm::lookAtLH + glm::perspectiveLH_ZO.
inline constexpr float kEye[3] = {0.0f, 4.0f, -9.0f};
inline constexpr float kTarget[3] = {0.0f, 0.5f, 0.0f};
inline constexpr float kFovYDegrees = 50.0f;
inline constexpr float kNear = 0.1f;
inline constexpr float kFar = 100.0f;

// Direction the light travels (normalised by the app and the test).
inline constexpr float kLightDir[3] = {-0.4f, -1.0f, 0.6f};
inline constexpr float kLightColor[3] = {0.9f, 0.85f, 0.8f};
inline constexpr float kAmbient[3] = {0.15f, 0.17f, 0.22f};

// Clear ("sky") colour, linear; the sRGB target encodes it.
inline constexpr float kClearColor[4] = {0.25f, 0.45f, 0.8f, 1.0f};

// Ground: a square of side kGroundSize at y = 0, the texture repeated kGroundRepeat times.
inline constexpr float kGroundSize = 24.0f;
inline constexpr float kGroundRepeat = 6.0f;
inline constexpr float kGroundTint[3] = {1.0f, 1.0f, 1.0f};

// The procedural texture: kTextureSize^2 texels, a checker of kCheckerCells^2 cells,
// sRGB colours (bytes, RGBA8_UNORM_SRGB), with thin darker "mortar" lines along the
// cell borders (kMortarTexels wide) so it reads as tiles.
inline constexpr uint32_t kTextureSize = 256;
inline constexpr uint32_t kCheckerCells = 4;
inline constexpr uint32_t kMortarTexels = 4;
inline constexpr uint8_t kCheckerA[3] = {200, 190, 170};
inline constexpr uint8_t kCheckerB[3] = {140, 60, 45};
inline constexpr uint8_t kMortar[3] = {70, 70, 70};

}  // namespace demo
