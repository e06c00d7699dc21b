#include "render/image.hpp"

#include <cairo.h>

namespace rangefit::render {

Image::Image(int w, int h, Rgb fill) : width(w), height(h) {
  const std::uint32_t word = (std::uint32_t{fill.r} << 16) | (std::uint32_t{fill.g} << 8) | fill.b;
  pixels.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), word);
}

Rgb Image::at(int x, int y) const {
  const std::uint32_t w = pixels[static_cast<std::size_t>(y) * width + x];
  return {static_cast<std::uint8_t>(w >> 16), static_cast<std::uint8_t>(w >> 8),
          static_cast<std::uint8_t>(w)};
}

void Image::set(int x, int y, Rgb c) {
  pixels[static_cast<std::size_t>(y) * width + x] =
      (std::uint32_t{c.r} << 16) | (std::uint32_t{c.g} << 8) | c.b;
}

bool write_png(const Image& image, const std::string& path, std::string* error) {
  if (image.width <= 0 || image.height <= 0) {
    *error = path + ": empty image";
    return false;
  }
  // cairo only reads the buffer here; its API takes a non-const pointer.
  auto* data = reinterpret_cast<unsigned char*>(const_cast<std::uint32_t*>(image.pixels.data()));
  cairo_surface_t* surface = cairo_image_surface_create_for_data(
      data, CAIRO_FORMAT_RGB24, image.width, image.height, image.width * 4);
  const cairo_status_t status = cairo_surface_write_to_png(surface, path.c_str());
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) {
    *error = path + ": " + cairo_status_to_string(status);
    return false;
  }
  return true;
}

}  // namespace rangefit::render
