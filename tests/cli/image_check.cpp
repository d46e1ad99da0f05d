// SPDX-License-Identifier: MIT
// Checks an image written by `calder render` or `calder window` (tests/cli).
//
//   image_check FILE [CHECK...]
//
// FILE is a PNG (read with Cairo) or a GIF (read with giflib and composed
// frame by frame, as a browser shows it). Checks, all in image pixels (a
// point (x, y) is the pixel floor(x), floor(y)):
//
//   --size W H              the image is W x H pixels
//   --frames N              a GIF has N frames (a PNG has 1)
//   --loop                  a GIF loops forever (NETSCAPE2.0, loop count 0)
//   --frame K               the pixel checks after it look at frame K (default 0)
//   --scale S               the checks after it give points and radii in canvas pixels:
//                           times S in the image (default 1)
//   --pad P                 radii of the checks after it are P larger (canvas pixels;
//                           default 0)
//   --gray X Y V TOL        the pixel at (X, Y) is opaque gray V: r, g and b within TOL of V
//   --gray-near X Y R V TOL at least half the pixels within R of (X, Y) are such a gray
//   --dark-near X Y R MAX   some pixel within R of (X, Y) has r, g and b <= MAX
//   --not-dark-near X Y R MAX  no pixel within R of (X, Y) has r, g and b <= MAX
//   --equals OTHER          frame K equals frame 0 of image OTHER (r, g, b and alpha
//                           of every pixel)
//   --colored-near X Y R    some pixel within R of (X, Y) is not gray (its r, g and b
//                           differ by more than 40: a force vector, a legend)
//   --print                 prints "size W H", "frames N", "loop yes|no"
//
// Exit 0 when every check holds; otherwise 1, with one line on stderr per
// failed check (and 2 for bad usage or an unreadable file).
#include <cairo.h>
#include <gif_lib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Rgba {
  int r = 255;
  int g = 255;
  int b = 255;
  int a = 255;
};

// An image as frames of RGBA pixels.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::vector<Rgba>> frames;
  std::optional<int> loop_count;  // GIF: NETSCAPE2.0's count, 0 = forever

  [[nodiscard]] const Rgba& at(std::size_t frame, int x, int y) const {
    return frames.at(frame).at(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(x));
  }
};

struct Usage : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Image read_png(const std::string& path) {
  cairo_surface_t* surface = cairo_image_surface_create_from_png(path.c_str());
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    const std::string why = cairo_status_to_string(cairo_surface_status(surface));
    cairo_surface_destroy(surface);
    throw Usage(path + ": cannot read the PNG: " + why);
  }
  cairo_surface_flush(surface);
  Image image;
  image.width = cairo_image_surface_get_width(surface);
  image.height = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const cairo_format_t format = cairo_image_surface_get_format(surface);
  std::vector<Rgba> pixels;
  pixels.reserve(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      std::uint32_t word = 0;
      std::memcpy(&word, data + static_cast<std::ptrdiff_t>(y) * stride + x * 4, 4);
      Rgba p;
      p.a = format == CAIRO_FORMAT_ARGB32 ? static_cast<int>(word >> 24) : 255;
      const auto unpremultiply = [&](std::uint32_t c) {
        if (p.a == 0) return 0;
        return static_cast<int>((c * 255 + static_cast<std::uint32_t>(p.a) / 2) /
                                static_cast<std::uint32_t>(p.a));
      };
      p.r = unpremultiply((word >> 16) & 0xff);
      p.g = unpremultiply((word >> 8) & 0xff);
      p.b = unpremultiply(word & 0xff);
      pixels.push_back(p);
    }
  }
  cairo_surface_destroy(surface);
  image.frames.push_back(std::move(pixels));
  return image;
}

std::optional<int> netscape_loop(const ExtensionBlock* blocks, int count) {
  for (int i = 0; i + 1 < count; ++i) {
    const ExtensionBlock& b = blocks[i];
    if (b.Function == APPLICATION_EXT_FUNC_CODE && b.ByteCount == 11 &&
        std::memcmp(b.Bytes, "NETSCAPE2.0", 11) == 0) {
      const ExtensionBlock& sub = blocks[i + 1];
      if (sub.ByteCount >= 3 && sub.Bytes[0] == 1) return sub.Bytes[1] | (sub.Bytes[2] << 8);
    }
  }
  return std::nullopt;
}

Image read_gif(const std::string& path) {
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
  if (gif == nullptr) throw Usage(path + ": cannot open the GIF: " + GifErrorString(error));
  if (DGifSlurp(gif) != GIF_OK) {
    const std::string why = GifErrorString(gif->Error);
    DGifCloseFile(gif, &error);
    throw Usage(path + ": cannot read the GIF: " + why);
  }
  Image image;
  image.width = gif->SWidth;
  image.height = gif->SHeight;
  const std::size_t size =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  std::vector<Rgba> screen(size, Rgba{255, 255, 255, 0});  // transparent before the first frame
  for (int k = 0; k < gif->ImageCount; ++k) {
    const SavedImage& frame = gif->SavedImages[k];
    if (k == 0) image.loop_count = netscape_loop(frame.ExtensionBlocks, frame.ExtensionBlockCount);
    GraphicsControlBlock gcb{};
    gcb.TransparentColor = NO_TRANSPARENT_COLOR;
    gcb.DisposalMode = DISPOSAL_UNSPECIFIED;
    DGifSavedExtensionToGCB(gif, k, &gcb);
    const ColorMapObject* map =
        frame.ImageDesc.ColorMap != nullptr ? frame.ImageDesc.ColorMap : gif->SColorMap;
    if (map == nullptr) throw Usage(path + ": frame " + std::to_string(k) + " has no palette");
    const std::vector<Rgba> before = screen;
    const GifImageDesc& d = frame.ImageDesc;
    for (int y = 0; y < d.Height; ++y) {
      for (int x = 0; x < d.Width; ++x) {
        const int index = frame.RasterBits[y * d.Width + x];
        if (index == gcb.TransparentColor) continue;
        const int sx = d.Left + x;
        const int sy = d.Top + y;
        if (sx < 0 || sy < 0 || sx >= image.width || sy >= image.height) continue;
        if (index >= map->ColorCount) throw Usage(path + ": a colour index out of the palette");
        const GifColorType c = map->Colors[index];
        screen[static_cast<std::size_t>(sy) * static_cast<std::size_t>(image.width) +
               static_cast<std::size_t>(sx)] = Rgba{c.Red, c.Green, c.Blue, 255};
      }
    }
    image.frames.push_back(screen);
    if (gcb.DisposalMode == DISPOSE_BACKGROUND) {
      for (int y = d.Top; y < d.Top + d.Height && y < image.height; ++y) {
        for (int x = d.Left; x < d.Left + d.Width && x < image.width; ++x) {
          screen[static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                 static_cast<std::size_t>(x)] = Rgba{255, 255, 255, 0};
        }
      }
    } else if (gcb.DisposalMode == DISPOSE_PREVIOUS) {
      screen = before;
    }
  }
  if (!image.loop_count)
    image.loop_count = netscape_loop(gif->ExtensionBlocks, gif->ExtensionBlockCount);
  DGifCloseFile(gif, &error);
  return image;
}

double number(char** argv, int& i, int argc, const char* what) {
  if (i + 1 >= argc) throw Usage(std::string("missing ") + what);
  ++i;
  char* end = nullptr;
  const double value = std::strtod(argv[i], &end);
  if (end == argv[i] || *end != '\0' || !std::isfinite(value)) {
    throw Usage(std::string("bad ") + what + ": '" + argv[i] + "'");
  }
  return value;
}

// snprintf, not operator+ on a literal and std::to_string: GCC 12 at -O3
// reports a false -Wrestrict in the inlined string concatenation (GCC PR 105329).
std::string rgba_text(const Rgba& p) {
  char text[64];
  std::snprintf(text, sizeof text, "(%d, %d, %d, alpha %d)", p.r, p.g, p.b, p.a);
  return text;
}

// Calls f(x, y) for each pixel whose centre is within r of (cx, cy).
template <class F>
void for_disk(const Image& image, double cx, double cy, double r, F&& f) {
  const int x0 = std::max(0, static_cast<int>(std::floor(cx - r)));
  const int x1 = std::min(image.width - 1, static_cast<int>(std::ceil(cx + r)));
  const int y0 = std::max(0, static_cast<int>(std::floor(cy - r)));
  const int y1 = std::min(image.height - 1, static_cast<int>(std::ceil(cy + r)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double dx = x + 0.5 - cx;
      const double dy = y + 0.5 - cy;
      if (dx * dx + dy * dy <= r * r) f(x, y);
    }
  }
}

bool is_gray(const Rgba& p, double value, double tolerance) {
  return p.a == 255 && std::abs(p.r - value) <= tolerance && std::abs(p.g - value) <= tolerance &&
         std::abs(p.b - value) <= tolerance;
}

bool is_dark(const Rgba& p, double max) {
  return p.a > 0 && p.r <= max && p.g <= max && p.b <= max;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: image_check FILE [--size W H] [--frames N] [--loop] ...\n");
    return 2;
  }
  const std::string path = argv[1];
  int failures = 0;
  const auto fail = [&](const std::string& what) {
    std::fprintf(stderr, "image_check: %s: %s\n", path.c_str(), what.c_str());
    ++failures;
  };
  try {
    const Image image = path.ends_with(".gif") ? read_gif(path) : read_png(path);
    std::size_t frame = 0;
    double scale = 1.0;
    double pad = 0.0;
    for (int i = 2; i < argc; ++i) {
      const std::string flag = argv[i];
      if (flag == "--print") {
        std::printf("size %d %d\nframes %zu\nloop %s\n", image.width, image.height,
                    image.frames.size(), image.loop_count && *image.loop_count == 0 ? "yes" : "no");
      } else if (flag == "--size") {
        const double w = number(argv, i, argc, "width");
        const double h = number(argv, i, argc, "height");
        if (image.width != static_cast<int>(w) || image.height != static_cast<int>(h)) {
          fail("size is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
               ", expected " + argv[i - 1] + "x" + argv[i]);
        }
      } else if (flag == "--frames") {
        const double n = number(argv, i, argc, "frame count");
        if (image.frames.size() != static_cast<std::size_t>(n)) {
          fail(std::to_string(image.frames.size()) + " frames, expected " + argv[i]);
        }
      } else if (flag == "--loop") {
        if (!image.loop_count || *image.loop_count != 0) {
          fail(image.loop_count ? "loops " + std::to_string(*image.loop_count) + " times"
                                : "has no NETSCAPE2.0 loop extension");
        }
      } else if (flag == "--frame") {
        frame = static_cast<std::size_t>(number(argv, i, argc, "frame"));
        if (frame >= image.frames.size())
          throw Usage("--frame " + std::string(argv[i]) + ": no such frame");
      } else if (flag == "--scale") {
        scale = number(argv, i, argc, "scale");
      } else if (flag == "--pad") {
        pad = number(argv, i, argc, "pad");
      } else if (flag == "--gray") {
        const double x = number(argv, i, argc, "x") * scale;
        const double y = number(argv, i, argc, "y") * scale;
        const double v = number(argv, i, argc, "gray");
        const double tol = number(argv, i, argc, "tolerance");
        const int px = static_cast<int>(std::floor(x));
        const int py = static_cast<int>(std::floor(y));
        if (px < 0 || py < 0 || px >= image.width || py >= image.height) {
          fail("(" + std::to_string(px) + ", " + std::to_string(py) + ") is outside the image");
          continue;
        }
        const Rgba& p = image.at(frame, px, py);
        if (!is_gray(p, v, tol)) {
          fail("pixel (" + std::to_string(px) + ", " + std::to_string(py) + ") of frame " +
               std::to_string(frame) + " is " + rgba_text(p) + ", expected gray " + argv[i - 1] +
               " +- " + argv[i]);
        }
      } else if (flag == "--gray-near") {
        const double x = number(argv, i, argc, "x") * scale;
        const double y = number(argv, i, argc, "y") * scale;
        const double r = (number(argv, i, argc, "radius") + pad) * scale;
        const double v = number(argv, i, argc, "gray");
        const double tol = number(argv, i, argc, "tolerance");
        int total = 0;
        int matching = 0;
        for_disk(image, x, y, r, [&](int px, int py) {
          ++total;
          if (is_gray(image.at(frame, px, py), v, tol)) ++matching;
        });
        if (total == 0 || matching * 2 < total) {
          fail(std::to_string(matching) + " of " + std::to_string(total) + " pixels within " +
               argv[i - 2] + " of (" + argv[i - 4] + ", " + argv[i - 3] + ") are gray " +
               argv[i - 1] + " +- " + argv[i] + "; expected at least half");
        }
      } else if (flag == "--dark-near" || flag == "--not-dark-near") {
        const double x = number(argv, i, argc, "x") * scale;
        const double y = number(argv, i, argc, "y") * scale;
        const double r = (number(argv, i, argc, "radius") + pad) * scale;
        const double max = number(argv, i, argc, "darkness");
        int dark = 0;
        for_disk(image, x, y, r, [&](int px, int py) {
          if (is_dark(image.at(frame, px, py), max)) ++dark;
        });
        const bool want_dark = flag == "--dark-near";
        if (want_dark && dark == 0) {
          fail(std::string("no pixel within ") + argv[i - 1] + " of (" + argv[i - 3] + ", " +
               argv[i - 2] + ") is dark (<= " + argv[i] + ")");
        } else if (!want_dark && dark > 0) {
          fail(std::to_string(dark) + " pixels within " + argv[i - 1] + " of (" + argv[i - 3] +
               ", " + argv[i - 2] + ") are dark (<= " + argv[i] + ")");
        }
      } else if (flag == "--colored-near") {
        const double x = number(argv, i, argc, "x") * scale;
        const double y = number(argv, i, argc, "y") * scale;
        const double r = (number(argv, i, argc, "radius") + pad) * scale;
        int colored = 0;
        for_disk(image, x, y, r, [&](int px, int py) {
          const Rgba& p = image.at(frame, px, py);
          const int spread = std::max({p.r, p.g, p.b}) - std::min({p.r, p.g, p.b});
          if (p.a > 0 && spread > 40) ++colored;
        });
        if (colored == 0) {
          fail(std::string("no coloured pixel within ") + argv[i] + " of (" + argv[i - 2] + ", " +
               argv[i - 1] + ")");
        }
      } else if (flag == "--equals") {
        if (i + 1 >= argc) throw Usage("missing the other image");
        const std::string other_path = argv[++i];
        const Image other =
            other_path.ends_with(".gif") ? read_gif(other_path) : read_png(other_path);
        if (other.width != image.width || other.height != image.height) {
          fail("is " + std::to_string(image.width) + "x" + std::to_string(image.height) + ", " +
               other_path + " is " + std::to_string(other.width) + "x" +
               std::to_string(other.height));
          continue;
        }
        int different = 0;
        std::string first;
        for (int y = 0; y < image.height; ++y) {
          for (int x = 0; x < image.width; ++x) {
            const Rgba& a = image.at(frame, x, y);
            const Rgba& b = other.at(0, x, y);
            if (a.r != b.r || a.g != b.g || a.b != b.b || a.a != b.a) {
              if (different++ == 0) {
                first = "(" + std::to_string(x) + ", " + std::to_string(y) + "): " + rgba_text(a) +
                        " vs " + rgba_text(b);
              }
            }
          }
        }
        if (different > 0) {
          fail("frame " + std::to_string(frame) + " differs from " + other_path + " in " +
               std::to_string(different) + " pixels, first " + first);
        }
      } else {
        throw Usage("unknown check '" + flag + "'");
      }
    }
  } catch (const Usage& e) {
    std::fprintf(stderr, "image_check: %s\n", e.what());
    return 2;
  }
  return failures == 0 ? 0 : 1;
}
