// The replay's own image drawing for its reports (replay --compare): an RGBA8 canvas
// with filled rectangles, lines, points, pasted images and text. Text is
// stb_easy_font's bitmap glyphs (Debian's libstb-dev), filled as the rectangles it
// gives; PNGs are written with stb_image_write by the caller.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

struct Rgb {
  uint8_t r, g, b;
};

class Canvas {
 public:
  Canvas(int width, int height, Rgb background);
  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<uint8_t>& pixels() const { return pixels_; }

  void Fill(int x, int y, int w, int h, Rgb colour);  // clipped to the canvas
  void Line(int x0, int y0, int x1, int y1, Rgb colour, int thickness = 1);
  void Point(int x, int y, int radius, Rgb colour);  // a filled disc
  // An RGBA8 image (tightly packed rows) with its top-left corner at (x, y).
  void Paste(const std::vector<uint8_t>& rgba, int w, int h, int x, int y);
  // Text with its top-left corner at (x, y), each glyph pixel `scale` canvas pixels.
  void Text(int x, int y, const std::string& text, Rgb colour, int scale = 1);
  static int TextWidth(const std::string& text, int scale = 1);
  static int TextHeight(int scale = 1);

 private:
  int width_, height_;
  std::vector<uint8_t> pixels_;
};
