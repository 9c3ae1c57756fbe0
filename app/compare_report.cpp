#include "compare_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <stb_image_write.h>

#include "canvas.h"
#include "renderer/image_metrics.h"

using renderer::MethodResult;
using renderer::SceneComparison;

namespace {

constexpr Rgb kWhite{255, 255, 255}, kInk{20, 20, 20}, kGrey{150, 150, 150}, kLight{225, 225, 225};

std::string Format(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

bool WritePng(const std::string& path, const Canvas& canvas, std::string* error) {
  if (stbi_write_png(path.c_str(), canvas.width(), canvas.height(), 4, canvas.pixels().data(), canvas.width() * 4))
    return true;
  return *error = "cannot write " + path, false;
}

bool Measured(const SceneComparison& scene, const MethodResult& r) { return scene.reference && !r.refused; }

// ---- comparison.md ----

std::string Row(const SceneComparison& scene, const MethodResult& r) {
  std::string row = "| " + std::string(r.method->name) + " | ";
  const std::string ms = r.timed ? Format("%.3f", r.gpuMs) : std::string("n/a");
  if (r.refused) return row + "refused: " + r.reason + " | | | | | | |\n";
  if (!Measured(scene, r))
    return row + "| | | | " + Format("%.1f", r.bytesPerPixel) + " | " + ms + " | no exact reference |\n";
  const bool reference = r.method == scene.reference;
  row += Format("%.3f", r.rmse) + " | " + (std::isinf(r.psnr) ? std::string("∞") : Format("%.2f", r.psnr)) + " | " +
         Format("%.4f", r.ssim) + " | " + Format("%.2f %%", 100.0 * r.shareOff) + " | " +
         Format("%.1f", r.bytesPerPixel) + " | " + ms + " | ";
  if (reference) row += "the reference";
  if (r.lostFragments) row += std::string(reference ? "; " : "") + std::to_string(r.lostFragments) + " fragments lost";
  return row + " |\n";
}

}  // namespace

std::string ParetoFile(const SceneComparison& scene) { return std::string("pareto_") + scene.scene->name + ".png"; }

bool WriteComparisonMarkdown(const std::string& path, const CompareRun& run, const std::vector<SceneComparison>& scenes,
                             std::string* error) {
  std::ofstream md(path);
  if (!md) return *error = "cannot write " + path, false;
  const renderer::ComparisonSettings& s = run.settings;
  md << "# Every method on every scene\n\n"
     << "`" << run.command << "` on " << run.adapter << ", " << s.width << "x" << s.height << ".\n\n"
     << "![every method on every scene](compare_grid.png)\n\n"
     << "Each scene's reference is its exact result: the first registered exact method that accepts the scene "
        "(`Exactness::kExact`, else `kExactWithEnoughLayers` peeled to the scene's layer count), which composites "
        "every fragment with its object's own per-surface model (the shards: coloured transmission). Every method "
        "renders the same frame of the replay.\n\n"
     << "- **RMSE**: over R, G and B of the 8-bit sRGB output, in 8-bit steps; **PSNR**: 20 log10(255 / RMSE) "
        "(peak 255).\n"
     << "- **SSIM**: the mean over every 11x11 Gaussian window (sigma 1.5) inside the image of the luma "
        "Y' = 0.299 R' + 0.587 G' + 0.114 B' of the sRGB values; K1 = 0.01, K2 = 0.03, L = 255.\n"
     << "- **> 2/255**: the share of pixels where some channel is off by more than 2 steps.\n"
     << "- **bytes/pixel**: the targets and buffers the method made for the frame (`Method::MemoryBytes`) per "
        "pixel, at the layer count the row ran with.\n"
     << "- **GPU ms**: the method's passes (not the opaque pass and the particle update) from TIMESTAMP queries, "
        "the median over the method drawing the compared frame again " << s.timedFrames << " more time(s).\n"
     << "- **fragments**: the translucent fragments past the opaque depth test (pixel-shader invocations of the "
        "reference's first pass).\n";
  for (const SceneComparison& scene : scenes) {
    md << "\n## " << scene.scene->name << "\n\n*" << scene.scene->summary << "*. Frame " << scene.frame << ", "
       << scene.fragments << " translucent fragments";
    if (scene.layers)
      md << ", " << scene.layers << " depth layers" << (scene.layersComplete ? "" : " or more (peeled no deeper)")
         << ": the peeling methods ran with " << scene.layers + (scene.layers & 1);
    md << ". Reference: " << (scene.reference ? scene.reference->name : "none (no exact method accepts the scene)")
       << ".\n\n"
       << "| method | RMSE | PSNR dB | SSIM | > 2/255 | bytes/pixel | GPU ms | |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---|\n";
    for (const MethodResult& r : scene.methods) md << Row(scene, r);
    if (scene.reference) md << "\n![" << scene.scene->name << ": error against GPU time](" << ParetoFile(scene) << ")\n";
  }
  return bool(md) || (*error = "cannot write " + path, false);
}

// ---- compare_grid.png ----

namespace {

constexpr int kGap = 4;

// `text` in lines that fit `width` pixels at `scale`, broken after hyphens and spaces.
std::vector<std::string> Wrap(const std::string& text, int width, int scale) {
  std::vector<std::string> lines{""};
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find_first_of("- ", start);
    end = end == std::string::npos ? text.size() : end + 1;
    const std::string word = text.substr(start, end - start);
    if (!lines.back().empty() && Canvas::TextWidth(lines.back() + word, scale) > width) lines.emplace_back();
    lines.back() += word;
    start = end;
  }
  return lines;
}

void HeatLegend(Canvas& c, int x, int y, int scale) {
  const int w = 256 * scale, h = 10 * scale;
  for (int i = 0; i < w; ++i) {
    uint8_t rgb[3];
    renderer::HeatColour(double(i) * kHeatFullScale / (w - 1), kHeatFullScale, rgb);
    c.Fill(x + i, y, 1, h, {rgb[0], rgb[1], rgb[2]});
  }
  c.Text(x, y + h + 3, "0", kInk, scale);
  const std::string full = std::to_string(kHeatFullScale) + "/255";
  c.Text(x + w - Canvas::TextWidth(full, scale), y + h + 3, full, kInk, scale);
  c.Text(x + w + 12 * scale, y,
         "error heat map: the largest channel difference to the exact reference, square-root scale", kInk, scale);
}

}  // namespace

bool WriteCompareGrid(const std::string& path, const CompareRun& run, const std::vector<SceneComparison>& scenes,
                      std::string* error) {
  const int w = int(run.settings.width), h = int(run.settings.height);
  // Text twice the glyphs' size in cells wide enough for it to stay legible when the
  // grid is shown scaled down.
  const int scale = w >= 240 ? 2 : 1, line = Canvas::TextHeight(scale) + 2 * scale;
  const int pad = 8 * scale, caption = line + 2 * scale;
  const size_t columns = scenes.empty() ? 0 : scenes.front().methods.size();
  int labelWidth = Canvas::TextWidth("reference:", scale);
  for (const SceneComparison& s : scenes)
    labelWidth = std::max({labelWidth, Canvas::TextWidth(s.scene->name, 2 * scale),
                           Canvas::TextWidth(s.reference ? s.reference->name : "none", scale)});
  labelWidth += 2 * pad;
  size_t headerLines = 1;
  for (const MethodResult& r : scenes.empty() ? std::vector<MethodResult>{} : scenes.front().methods)
    headerLines = std::max(headerLines, Wrap(r.method->name, w, scale).size());
  const int header = int(headerLines) * line + pad;
  const int block = 2 * (h + caption) + kGap + 2 * pad;  // images, heat maps, their captions
  const int legend = 40 * scale;
  Canvas c(labelWidth + int(columns) * (w + kGap) + pad, header + int(scenes.size()) * block + legend, kWhite);

  for (size_t i = 0; i < columns; ++i) {
    int y = pad / 2;
    for (const std::string& text : Wrap(scenes.front().methods[i].method->name, w, scale)) {
      c.Text(labelWidth + int(i) * (w + kGap), y, text, kInk, scale);
      y += line;
    }
  }
  for (size_t row = 0; row < scenes.size(); ++row) {
    const SceneComparison& scene = scenes[row];
    const int top = header + int(row) * block, heatTop = top + pad + h + caption + kGap;
    c.Fill(0, top, c.width(), scale, kLight);
    c.Text(pad, top + pad, scene.scene->name, kInk, 2 * scale);
    c.Text(pad, heatTop, "error", kInk, scale);
    c.Text(pad, heatTop + line, "reference:", kGrey, scale);
    c.Text(pad, heatTop + 2 * line, scene.reference ? scene.reference->name : "none", kGrey, scale);
    for (size_t i = 0; i < scene.methods.size(); ++i) {
      const MethodResult& r = scene.methods[i];
      const int x = labelWidth + int(i) * (w + kGap), imageY = top + pad;
      if (r.refused) {
        c.Fill(x, imageY, w, h, kLight);
        c.Text(x + 4, imageY + 4, "refused", kInk, scale);
        int y = imageY + 4 + line;
        for (const std::string& text : Wrap(r.reason, w - 8, 1))  // the reason small: it is long
          if (y + Canvas::TextHeight() < imageY + h) c.Text(x + 4, y, text, kGrey), y += Canvas::TextHeight() + 1;
        continue;
      }
      c.Paste(r.image, w, h, x, imageY);
      if (!Measured(scene, r)) continue;
      const MethodResult& reference = *scene.Find(scene.reference->name);
      c.Paste(renderer::ErrorHeatMap(r.image, reference.image, kHeatFullScale), w, h, x, heatTop);
      std::string text = r.method == scene.reference
                             ? "reference"
                             : "RMSE " + Format("%.2f", r.rmse) + "  SSIM " + Format("%.3f", r.ssim);
      if (Canvas::TextWidth(text, scale) > w) text = "RMSE " + Format("%.2f", r.rmse);  // a narrow cell
      c.Text(x, heatTop + h + 2 * scale, text, kInk, scale);
    }
  }
  HeatLegend(c, pad, c.height() - legend + 4 * scale, scale);
  return WritePng(path, c, error);
}

// ---- pareto_<scene>.png ----

namespace {

struct Box {
  int x, y, w, h;
  bool Overlaps(const Box& o) const { return x < o.x + o.w && o.x < x + w && y < o.y + o.h && o.y < y + h; }
};

// GPU ms on a log scale (the methods span four decades), RMSE on a linear one.
bool WritePareto(const std::string& path, const SceneComparison& scene, std::string* error) {
  std::vector<const MethodResult*> points;
  for (const MethodResult& r : scene.methods)
    if (Measured(scene, r) && r.timed && r.gpuMs > 0) points.push_back(&r);
  const int width = 640, height = 420, left = 64, right = 24, top = 36, bottom = 48;
  Canvas c(width, height, kWhite);
  const int plotW = width - left - right, plotH = height - top - bottom;
  double minMs = 1e30, maxMs = 0, maxRmse = 0;
  for (const MethodResult* r : points)
    minMs = std::min(minMs, r->gpuMs), maxMs = std::max(maxMs, r->gpuMs), maxRmse = std::max(maxRmse, r->rmse);
  const int firstDecade = points.empty() ? 0 : int(std::floor(std::log10(minMs)));
  const int lastDecade = points.empty() ? 1 : std::max(firstDecade + 1, int(std::ceil(std::log10(maxMs))));
  double yStep = 1;
  for (double step : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0})
    if ((yStep = step) * 5 >= maxRmse * 1.05) break;
  const double yMax = std::max(1.0, std::ceil(maxRmse * 1.05 / yStep)) * yStep;
  auto px = [&](double ms) {
    return left + int(std::lround((std::log10(ms) - firstDecade) / (lastDecade - firstDecade) * plotW));
  };
  auto py = [&](double rmse) { return top + plotH - int(std::lround(rmse / yMax * plotH)); };

  c.Text(left, 10, std::string(scene.scene->name) + ": RMSE to the exact reference (" + scene.reference->name +
                       ") against GPU ms of the method's passes", kInk);
  for (int decade = firstDecade; decade <= lastDecade; ++decade) {
    const double ms = std::pow(10.0, decade);
    c.Fill(px(ms), top, 1, plotH, kLight);
    for (int m = 2; m < 10 && decade < lastDecade; ++m) c.Fill(px(m * ms), top + plotH - 4, 1, 4, kGrey);
    const std::string label = Format("%g", ms);
    c.Text(px(ms) - Canvas::TextWidth(label) / 2, top + plotH + 6, label, kInk);
  }
  for (double y = 0; y <= yMax + yStep / 2; y += yStep) {
    c.Fill(left, py(y), plotW, 1, kLight);
    const std::string label = Format("%g", y);
    c.Text(left - 6 - Canvas::TextWidth(label), py(y) - 4, label, kInk);
  }
  c.Line(left, top, left, top + plotH, kInk), c.Line(left, top + plotH, left + plotW, top + plotH, kInk);
  c.Text(left + plotW / 2 - 60, height - 20, "GPU ms (log scale)", kInk);
  c.Text(6, top - 14, "RMSE (8-bit steps)", kInk);

  // The Pareto front: each point that no faster (or equally fast) point matches in error.
  std::vector<const MethodResult*> byTime = points;
  std::sort(byTime.begin(), byTime.end(),
            [](auto* a, auto* b) { return a->gpuMs < b->gpuMs || (a->gpuMs == b->gpuMs && a->rmse < b->rmse); });
  std::vector<const MethodResult*> front;
  for (const MethodResult* r : byTime)
    if (front.empty() || r->rmse < front.back()->rmse) front.push_back(r);
  const Rgb frontColour{200, 40, 30}, otherColour{60, 90, 160};
  for (size_t i = 1; i < front.size(); ++i)
    c.Line(px(front[i - 1]->gpuMs), py(front[i - 1]->rmse), px(front[i]->gpuMs), py(front[i]->rmse), frontColour, 2);
  std::vector<Box> labels;
  for (const MethodResult* r : byTime) {
    const bool onFront = std::find(front.begin(), front.end(), r) != front.end();
    c.Point(px(r->gpuMs), py(r->rmse), 4, onFront ? frontColour : otherColour);
    // Beside its point, moved down past the labels already placed.
    const std::string label = r->method->name;
    Box box{std::min(px(r->gpuMs) + 7, width - 2 - Canvas::TextWidth(label)), py(r->rmse) - 10,
            Canvas::TextWidth(label), Canvas::TextHeight()};
    for (int tries = 0; tries < 12 && std::any_of(labels.begin(), labels.end(), [&](const Box& b) { return b.Overlaps(box); });
         ++tries)
      box.y += Canvas::TextHeight();
    labels.push_back(box);
    c.Text(box.x, box.y, label, onFront ? frontColour : kInk);
  }
  c.Text(left + plotW - 140, top + 6, "red: the Pareto front", frontColour);
  return WritePng(path, c, error);
}

}  // namespace

bool WriteParetoPlots(const std::string& dir, const std::vector<SceneComparison>& scenes, std::string* error) {
  for (const SceneComparison& scene : scenes)
    if (scene.reference && !WritePareto((std::filesystem::path(dir) / ParetoFile(scene)).string(), scene, error))
      return false;
  return true;
}
