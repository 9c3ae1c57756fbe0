#include "canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include <stb_easy_font.h>

Canvas::Canvas(int width, int height, Rgb background)
    : width_(width), height_(height), pixels_(size_t(width) * height * 4, 255) {
  Fill(0, 0, width, height, background);
}

void Canvas::Fill(int x, int y, int w, int h, Rgb colour) {
  const int x0 = std::max(x, 0), y0 = std::max(y, 0), x1 = std::min(x + w, width_), y1 = std::min(y + h, height_);
  for (int j = y0; j < y1; ++j)
    for (int i = x0; i < x1; ++i) {
      uint8_t* p = &pixels_[(size_t(j) * width_ + i) * 4];
      p[0] = colour.r, p[1] = colour.g, p[2] = colour.b, p[3] = 255;
    }
}

// Bresenham's line, each step a thickness x thickness square.
void Canvas::Line(int x0, int y0, int x1, int y1, Rgb colour, int thickness) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0), sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    Fill(x0 - thickness / 2, y0 - thickness / 2, thickness, thickness, colour);
    if (x0 == x1 && y0 == y1) return;
    const int e2 = 2 * err;
    if (e2 >= dy) err += dy, x0 += sx;
    if (e2 <= dx) err += dx, y0 += sy;
  }
}

void Canvas::Point(int x, int y, int radius, Rgb colour) {
  for (int j = -radius; j <= radius; ++j)
    for (int i = -radius; i <= radius; ++i)
      if (i * i + j * j <= radius * radius) Fill(x + i, y + j, 1, 1, colour);
}

void Canvas::Paste(const std::vector<uint8_t>& rgba, int w, int h, int x, int y) {
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const uint8_t* s = &rgba[(size_t(j) * w + i) * 4];
      Fill(x + i, y + j, 1, 1, {s[0], s[1], s[2]});
    }
}

void Canvas::Text(int x, int y, const std::string& text, Rgb colour, int scale) {
  // stb_easy_font: 4 vertices of 16 bytes (x, y, z floats and a colour) per quad.
  std::vector<char> quads(text.size() * 300 + 64);
  std::vector<char> copy(text.begin(), text.end());
  copy.push_back('\0');
  const int count = stb_easy_font_print(0, 0, copy.data(), nullptr, quads.data(), int(quads.size()));
  for (int q = 0; q < count; ++q) {
    float corner[4][2];
    for (int v = 0; v < 4; ++v) std::memcpy(corner[v], &quads[size_t(q * 4 + v) * 16], sizeof corner[v]);
    const int left = int(std::lround(corner[0][0])), top = int(std::lround(corner[0][1]));
    const int right = int(std::lround(corner[2][0])), bottom = int(std::lround(corner[2][1]));
    Fill(x + left * scale, y + top * scale, (right - left) * scale, (bottom - top) * scale, colour);
  }
}

int Canvas::TextWidth(const std::string& text, int scale) {
  std::vector<char> copy(text.begin(), text.end());
  copy.push_back('\0');
  return stb_easy_font_width(copy.data()) * scale;
}

int Canvas::TextHeight(int scale) {
  char sample[] = "Ag";
  return stb_easy_font_height(sample) * scale;
}
