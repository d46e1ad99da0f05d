// SPDX-License-Identifier: MIT
// calder::render from an installed calder: a cleared 4 x 3 canvas is 48 bytes
// of transparent RGBA, and its PNG starts with the PNG signature.
#include <calder/render.hpp>
#include <cstdio>

int main() {
  calder::Canvas canvas(4, 3);
  canvas.clear();
  const auto rgba = canvas.rgba();
  bool transparent = rgba.size() == 4 * 3 * 4;
  for (std::size_t i = 3; i < rgba.size(); i += 4) transparent = transparent && rgba[i] == 0;
  const auto png = canvas.encode_png();
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  bool is_png = png.size() > 8;
  for (std::size_t i = 0; is_png && i < 8; ++i) is_png = png[i] == signature[i];
  if (!transparent || !is_png) {
    std::fprintf(stderr, "consumer_render: expected a transparent 4x3 image and a PNG\n");
    return 1;
  }
  std::printf("consumer_render: ok (%zu bytes of PNG)\n", png.size());
  return 0;
}
