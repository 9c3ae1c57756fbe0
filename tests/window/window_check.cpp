// window_check: `replay --window` under Xvfb (xvfb-run -a), checked against headless `replay`.
//
//   window_check --replay PATH --out DIR --demo D --method M --frames N [--size WxH] [--resize]
//
// 1. Runs headless `replay --demo D --method M --frames N --size WxH --out DIR/headless`
//    (frame N-1 as PNG), with the validation layer on (RHI_VALIDATION=1).
// 2. Runs `xvfb-run -a replay --window --validation ... --screenshot DIR/window.png --frames N`:
//    a GLFW window on Xvfb, a Vulkan surface on lavapipe (VK_KHR_xlib/xcb_surface), N frames,
//    then the back buffer (scene + ImGui overlay) read back through the RHI before Present.
//    Any validation-layer message makes replay exit 3, which fails here.
// 3. Pixels, with the overlay window's rectangle that replay prints ("overlay: x y w h"):
//    - the scene: every pixel outside the overlay (2 px margin) within 2 of the headless frame
//      (the window draws the scene 1:1 with point sampling into an R8G8B8A8_UNORM back buffer);
//    - the overlay body: at least 40% of its pixels are ImGui's dark style WindowBg
//      (0.06, 0.06, 0.06, 0.94 -> RGBA8 15, 15, 15, 240) blended SRC_ALPHA/INV_SRC_ALPHA over
//      the headless scene pixel (within 2) -- the rest is text and widgets -- and its mean
//      difference from the scene is large (the overlay is there, not the scene);
//    - the title bar: TitleBgActive (41, 74, 122) or TitleBg (10, 10, 10), within 2.
//   --resize: replay --test-resize (800x450 after 3 frames, then 500x400; the screenshot waits
//   for it): the PNG is 500x400, the letterbox bars above and below the scene are the clear
//   colour (20, 20, 23) and the scene between them is not.
// Exit codes: 0 pass, 1 fail, 77 skipped (no xvfb-run; ctest SKIP_RETURN_CODE).
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace {

int failures = 0;

void Check(bool ok, const std::string& what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAIL", what.c_str());
  if (!ok) ++failures;
}

std::string Quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs a shell command, echoes its output and returns its exit status and output.
int Run(const std::string& command, std::string* output) {
  std::printf("$ %s\n", command.c_str());
  std::fflush(stdout);
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output->append(buffer, n);
  const int status = pclose(pipe);
  std::fputs(output->c_str(), stdout);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Image {
  int w = 0, h = 0;
  std::vector<unsigned char> rgba;
  const unsigned char* At(int x, int y) const { return &rgba[(size_t(y) * w + x) * 4]; }
};

bool Load(const std::string& path, Image* image) {
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &image->w, &image->h, &channels, 4);
  if (!data) return false;
  image->rgba.assign(data, data + size_t(image->w) * image->h * 4);
  stbi_image_free(data);
  return true;
}

bool Near(const unsigned char* p, int r, int g, int b, int tolerance) {
  return std::abs(p[0] - r) <= tolerance && std::abs(p[1] - g) <= tolerance && std::abs(p[2] - b) <= tolerance;
}

std::string FindXvfbRun() {
  std::string out;
  FILE* pipe = popen("command -v xvfb-run", "r");
  if (!pipe) return "";
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
  pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string replay, outDir, demo = "smoke", method = "wboit", size = "640x360";
  int frames = 1;
  bool resize = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--replay") replay = next();
    else if (a == "--out") outDir = next();
    else if (a == "--demo") demo = next();
    else if (a == "--method") method = next();
    else if (a == "--frames") frames = std::atoi(next().c_str());
    else if (a == "--size") size = next();
    else if (a == "--resize") resize = true;
    else {
      std::fprintf(stderr, "window_check: unknown argument %s\n", a.c_str());
      return 1;
    }
  }
  int width = 0, height = 0;
  if (replay.empty() || outDir.empty() || frames <= 0 || std::sscanf(size.c_str(), "%dx%d", &width, &height) != 2) {
    std::fprintf(stderr, "usage: window_check --replay PATH --out DIR --demo D --method M --frames N [--size WxH]\n");
    return 1;
  }
  const std::string xvfbRun = FindXvfbRun();
  if (xvfbRun.empty()) {
    std::printf("SKIPPED: xvfb-run is not installed (Debian package xvfb, see ./run)\n");
    return 77;
  }
  std::filesystem::remove_all(outDir);
  std::filesystem::create_directories(outDir);

  // 1. The headless frame.
  const std::string headlessDir = outDir + "/headless";
  std::string output;
  int rc = Run("RHI_VALIDATION=1 " + Quote(replay) + " --demo " + demo + " --method " + method + " --frames " +
                   std::to_string(frames) + " --size " + size + " --out " + Quote(headlessDir),
               &output);
  Check(rc == 0, "headless replay exits 0 (got " + std::to_string(rc) + ")");
  char name[128];
  std::snprintf(name, sizeof name, "/%s_%s_%04d.png", demo.c_str(), method.c_str(), frames - 1);
  Image headless;
  Check(Load(headlessDir + name, &headless), std::string("headless PNG ") + name + " loads");

  // 2. The window under Xvfb. The X screen is larger than any window the test asks for.
  const std::string shot = outDir + "/window.png";
  output.clear();
  rc = Run(Quote(xvfbRun) + " -a -s '-screen 0 1280x1024x24' " + Quote(replay) + " --window --validation --demo " +
               demo + " --method " + method + " --frames " + std::to_string(frames) + " --size " + size +
               (resize ? " --test-resize" : "") + " --screenshot " + Quote(shot),
           &output);
  Check(rc == 0, "replay --window under xvfb-run exits 0, no validation message (got " + std::to_string(rc) + ")");
  Image window;
  if (!Load(shot, &window)) {
    Check(false, "screenshot " + shot + " loads");
    return 1;
  }
  int ox = 0, oy = 0, ow = 0, oh = 0;
  const size_t at = output.find("overlay: ");
  const bool parsed =
      at != std::string::npos && std::sscanf(output.c_str() + at, "overlay: %d %d %d %d", &ox, &oy, &ow, &oh) == 4;
  Check(parsed && ow > 40 && oh > 40,
        "replay printed the overlay rectangle (" + std::to_string(ox) + " " + std::to_string(oy) + " " +
            std::to_string(ow) + " " + std::to_string(oh) + ")");
  auto inOverlay = [&](int x, int y, int margin) {
    return x >= ox - margin && x < ox + ow + margin && y >= oy - margin && y < oy + oh + margin;
  };

  // 3. Title bar: right end of its first rows (the title text is on the left).
  bool title = false;
  for (int dy = 4; dy <= 10 && !title; ++dy) {
    const unsigned char* p = window.At(std::min(window.w - 1, ox + ow - 8), oy + dy);
    title = Near(p, 41, 74, 122, 2) || Near(p, 10, 10, 10, 2);
  }
  {
    const unsigned char* p = window.At(std::min(window.w - 1, ox + ow - 8), oy + 6);
    Check(title, "title bar has ImGui's TitleBgActive/TitleBg colour (pixel " + std::to_string(p[0]) + "," +
                     std::to_string(p[1]) + "," + std::to_string(p[2]) + ")");
  }

  if (resize) {
    Check(window.w == 500 && window.h == 400,
          "screenshot is the resized back buffer 500x400 (got " + std::to_string(window.w) + "x" +
              std::to_string(window.h) + ")");
    if (window.w != 500 || window.h != 400) return 1;
    // The scene (640x360 -> 500x281) is letterboxed: rows 0..58 and 340..399 are bars.
    const int sceneTop = (400 - 281) / 2, sceneBottom = sceneTop + 281;
    int barPixels = 0, barMatches = 0, scenePixels = 0, sceneClear = 0;
    for (int y = 0; y < window.h; ++y)
      for (int x = 0; x < window.w; ++x) {
        if (inOverlay(x, y, 2)) continue;
        const bool clear = Near(window.At(x, y), 20, 20, 23, 1);
        if (y < sceneTop - 1 || y > sceneBottom) ++barPixels, barMatches += clear;
        else if (y > sceneTop + 1 && y < sceneBottom - 2) ++scenePixels, sceneClear += clear;
      }
    Check(barPixels > 0 && barMatches == barPixels,
          "letterbox bars are the clear colour (" + std::to_string(barMatches) + " of " + std::to_string(barPixels) +
              ")");
    Check(scenePixels > 0 && sceneClear * 100 < scenePixels,
          "the scene fills the band between the bars (" + std::to_string(sceneClear) + " of " +
              std::to_string(scenePixels) + " pixels are the clear colour)");
  } else {
    Check(window.w == width && window.h == height && headless.w == width && headless.h == height,
          "screenshot and headless frame are " + size);
    if (window.w != headless.w || window.h != headless.h) return 1;

    // The scene outside the overlay equals the headless frame.
    long compared = 0, off = 0;
    int maxDiff = 0;
    double sum2 = 0;
    for (int y = 0; y < window.h; ++y)
      for (int x = 0; x < window.w; ++x) {
        if (inOverlay(x, y, 2)) continue;
        const unsigned char *a = window.At(x, y), *b = headless.At(x, y);
        int d = 0;
        for (int c = 0; c < 3; ++c) {
          d = std::max(d, std::abs(a[c] - b[c]));
          sum2 += double(a[c] - b[c]) * (a[c] - b[c]);
        }
        maxDiff = std::max(maxDiff, d);
        off += d > 2;
        ++compared;
      }
    char line[256];
    std::snprintf(line, sizeof line,
                  "scene outside the overlay matches the headless frame: %ld pixels, %ld off by more than 2, max "
                  "diff %d, RMSE %.3f",
                  compared, off, maxDiff, std::sqrt(sum2 / double(std::max(1L, compared) * 3)));
    Check(compared > 0 && off == 0, line);

    // The overlay body (below the title bar, inside the border) is ImGui's WindowBg over the scene.
    long body = 0, bg = 0;
    double diffSum = 0;
    const int titleHeight = 19;  // FontSize 13 + 2 * FramePadding.y 3
    for (int y = oy + titleHeight + 2; y < oy + oh - 2; ++y)
      for (int x = ox + 2; x < ox + ow - 2; ++x) {
        if (x >= window.w || y >= window.h) continue;
        const unsigned char *a = window.At(x, y), *s = headless.At(x, y);
        bool match = true;
        for (int c = 0; c < 3; ++c) {
          const double expected = (15.0 * 240.0 + s[c] * 15.0) / 255.0;
          match &= std::abs(a[c] - expected) <= 2.0;
          diffSum += std::abs(a[c] - s[c]);
        }
        bg += match;
        ++body;
      }
    std::snprintf(line, sizeof line, "overlay body is WindowBg over the scene: %ld of %ld pixels (%.1f%%)", bg, body,
                  body ? 100.0 * bg / body : 0.0);
    Check(body > 0 && bg * 100 >= body * 40, line);
    const double meanDiff = body ? diffSum / (3.0 * body) : 0;
    std::snprintf(line, sizeof line, "overlay differs from the scene: mean |window - headless| %.1f > 20", meanDiff);
    Check(meanDiff > 20, line);
  }

  std::printf("%s (%d failure%s)\n", failures ? "FAILED" : "PASSED", failures, failures == 1 ? "" : "s");
  return failures ? 1 : 0;
}
