// demo_check DEMO OUTDIR: runs `DEMO --headless --out OUTDIR`, loads OUTDIR/demo_scene.png
// and compares pixels with values computed here on the CPU, independently of the GPU
// path and of GLM (the camera and the Lambert formula are re-implemented by hand from
// the scene parameters in app/scene_params.h):
//  * sky: the top corners show the clear colour, sRGB-encoded (|diff| <= 1 per channel);
//  * ground: the centres of two checker cells (one of each colour) in front of the
//    camera, projected to pixels with a hand-written left-handed look-at + perspective,
//    must be albedo * (ambient + light * max(0, N.-L)) with N = +y, the albedo decoded
//    from the texture's sRGB bytes and the result sRGB-encoded (|diff| <= 3).
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scene_params.h"

namespace {

struct V3 {
  double x, y, z;
};
V3 Sub(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double Dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 Cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 Normalize(V3 a) {
  const double l = std::sqrt(Dot(a, a));
  return {a.x / l, a.y / l, a.z / l};
}
V3 Of(const float v[3]) { return {v[0], v[1], v[2]}; }

double SrgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double LinearToSrgb(double c) {
  c = std::fmin(std::fmax(c, 0.0), 1.0);
  return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}
int Encode(double linear) { return static_cast<int>(std::lround(LinearToSrgb(linear) * 255.0)); }

// World point -> pixel (D3D: NDC y up, pixel y down), left-handed camera.
bool Project(V3 p, double* px, double* py) {
  const V3 eye = Of(demo::kEye), forward = Normalize(Sub(Of(demo::kTarget), eye));
  const V3 right = Normalize(Cross({0, 1, 0}, forward)), up = Cross(forward, right);
  const V3 d = Sub(p, eye);
  const double x = Dot(d, right), y = Dot(d, up), z = Dot(d, forward);
  if (z <= 0) return false;
  const double f = 1.0 / std::tan(demo::kFovYDegrees * M_PI / 360.0);
  const double aspect = double(demo::kWidth) / demo::kHeight;
  const double ndcX = f / aspect * x / z, ndcY = f * y / z;
  *px = (ndcX + 1) / 2 * demo::kWidth;
  *py = (1 - ndcY) / 2 * demo::kHeight;
  return true;
}

int failures = 0;

void Expect(const unsigned char* image, int x, int y, const int expected[3], int tolerance, const char* what) {
  const unsigned char* p = image + (static_cast<size_t>(y) * demo::kWidth + x) * 4;
  bool ok = true;
  for (int c = 0; c < 3; ++c) ok &= std::abs(p[c] - expected[c]) <= tolerance;
  std::printf("%-5s %-34s pixel (%3d,%3d) = (%3d,%3d,%3d), expected (%3d,%3d,%3d) +-%d\n", ok ? "ok" : "FAIL", what,
              x, y, p[0], p[1], p[2], expected[0], expected[1], expected[2], tolerance);
  if (!ok) ++failures;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: demo_check DEMO OUTDIR\n");
    return 2;
  }
  const std::string outDir = argv[2];
  const std::string png = outDir + "/demo_scene.png";
  std::remove(png.c_str());
  const std::string command = std::string("\"") + argv[1] + "\" --headless --out \"" + outDir + "\"";
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "FAIL: %s exited non-zero\n", command.c_str());
    return 1;
  }
  int w = 0, h = 0, n = 0;
  unsigned char* image = stbi_load(png.c_str(), &w, &h, &n, 4);
  if (!image) {
    std::fprintf(stderr, "FAIL: cannot load %s\n", png.c_str());
    return 1;
  }
  if (w != int(demo::kWidth) || h != int(demo::kHeight)) {
    std::fprintf(stderr, "FAIL: %s is %dx%d\n", png.c_str(), w, h);
    return 1;
  }

  // Sky: the clear colour through the sRGB target.
  const int sky[3] = {Encode(demo::kClearColor[0]), Encode(demo::kClearColor[1]), Encode(demo::kClearColor[2])};
  Expect(image, 0, 0, sky, 1, "sky (top-left)");
  Expect(image, w - 1, 0, sky, 1, "sky (top-right)");

  // Ground: one world unit per checker cell (texture repeated kGroundRepeat times over
  // kGroundSize); cell centres are at x, z = k + 0.5 when the cell size is 1.
  const double cellWorld = demo::kGroundSize / demo::kGroundRepeat / demo::kCheckerCells;
  const double lambert = std::fmax(0.0, Dot({0, 1, 0}, Normalize(Of(demo::kLightDir))) * -1.0);
  for (double x : {0.5, 1.5}) {
    const V3 p{x * cellWorld, 0, -4.5 * cellWorld};
    // Texture coordinates as the ground quad assigns them: u grows with x, v with -z.
    const double h2 = demo::kGroundSize / 2;
    const double u = (p.x + h2) / demo::kGroundSize * demo::kGroundRepeat;
    const double v = (h2 - p.z) / demo::kGroundSize * demo::kGroundRepeat;
    const int cx = int(std::floor((u - std::floor(u)) * demo::kCheckerCells));
    const int cy = int(std::floor((v - std::floor(v)) * demo::kCheckerCells));
    const unsigned char* albedo = (cx + cy) % 2 == 0 ? demo::kCheckerA : demo::kCheckerB;
    int expected[3];
    for (int c = 0; c < 3; ++c)
      expected[c] = Encode(SrgbToLinear(albedo[c] / 255.0) * demo::kGroundTint[c] *
                           (demo::kAmbient[c] + demo::kLightColor[c] * lambert));
    double px = 0, py = 0;
    if (!Project(p, &px, &py)) {
      std::fprintf(stderr, "FAIL: ground point behind the camera\n");
      return 1;
    }
    char what[64];
    std::snprintf(what, sizeof what, "ground cell centre (%.1f, 0, %.1f)", p.x, p.z);
    Expect(image, int(px), int(py), expected, 3, what);
  }
  stbi_image_free(image);
  std::printf("%s\n", failures ? "FAILED" : "PASSED");
  return failures ? 1 : 0;
}
