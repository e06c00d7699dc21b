#pragma once
// An opaque RGB picture in memory, laid out as cairo's RGB24 surface (one 0x00RRGGBB word per
// pixel, rows top to bottom), so the renderer draws into it directly and tests read it back.

#include <cstdint>
#include <string>
#include <vector>

namespace rangefit::render {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint32_t> pixels;  // width * height words, 0x00RRGGBB

  Image() = default;
  Image(int w, int h, Rgb fill);
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  Rgb at(int x, int y) const;
  void set(int x, int y, Rgb c);
};

// Writes the image as PNG; false and *error (the path and cairo's reason) when it cannot.
bool write_png(const Image& image, const std::string& path, std::string* error);

}  // namespace rangefit::render
