// SPDX-License-Identifier: MIT
// calder render: animated GIF output (giflib), with exact palettes when a
// frame has at most 256 colours and calder's quantiser's otherwise
// (quantize.hpp).
#include <gif_lib.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "../output/output.hpp"
#include "calder/error.hpp"
#include "calder/render.hpp"
#include "quantize.hpp"

namespace calder {

namespace {

constexpr int kMaxGifSide = 65535;

// The delay before frame `index + 1`, in hundredths of a second: rounded so
// that the frames keep time on average, at least 2 (browsers play shorter
// delays as 10).
int delay_cs(int index, double fps) {
  const double start = std::round(static_cast<double>(index) * 100.0 / fps);
  const double end = std::round(static_cast<double>(index + 1) * 100.0 / fps);
  return static_cast<int>(std::clamp(end - start, 2.0, 65535.0));
}

}  // namespace

struct GifWriter::Impl {
  output::AtomicFile file;
  GifFileType* gif = nullptr;
  int width = 0;
  int height = 0;
  double fps = 0.0;
  int frames = 0;
  bool finished = false;
  bool failed = false;
  std::vector<std::uint32_t> previous, current;  // 0x00RRGGBB
  std::vector<std::uint8_t> indices;

  explicit Impl(const std::string& path) : file("GifWriter", path) {}
  ~Impl() {
    if (gif != nullptr) {
      int error = 0;
      EGifCloseFile(gif, &error);  // closes its own descriptor
    }
    // file's destructor removes the temporary file unless committed.
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  [[noreturn]] void gif_failed(const char* what) {
    failed = true;
    const int error = gif != nullptr ? gif->Error : 0;
    throw Error(
        "GifWriter: cannot " + std::string(what) + " '" + detail::printable(file.path(), 240) +
        "': " + (GifErrorString(error) != nullptr ? GifErrorString(error) : "giflib error"));
  }
  void check(int result, const char* what) {
    if (result == GIF_ERROR) gif_failed(what);
  }
  void write_frame(int x0, int y0, int w, int h);
};

GifWriter::GifWriter(const std::string& path, int width, int height, double fps) {
  if (width < 1 || height < 1 || width > kMaxGifSide || height > kMaxGifSide) {
    throw Error("GifWriter: size must be 1..65535 pixels a side (got " + std::to_string(width) +
                " x " + std::to_string(height) + ")");
  }
  if (!(fps >= 0.01 && fps <= 100.0)) {
    throw Error("GifWriter: fps must be in [0.01, 100] (got " + detail::format_number(fps) + ")");
  }
  impl_ = std::make_unique<Impl>(path);
  Impl& d = *impl_;
  d.width = width;
  d.height = height;
  d.fps = fps;
  // giflib closes the descriptor it is given; the file keeps its own, to
  // sync and rename.
  const int fd = ::dup(d.file.fd());
  if (fd < 0) d.file.fail("write", errno);
  int error = 0;
  d.gif = EGifOpenFileHandle(fd, &error);
  if (d.gif == nullptr) {
    ::close(fd);
    throw Error("GifWriter: cannot write '" + path + "': " +
                (GifErrorString(error) != nullptr ? GifErrorString(error) : "giflib error"));
  }
  EGifSetGifVersion(d.gif, true);  // GIF89a: delays and the loop extension
  d.check(EGifPutScreenDesc(d.gif, width, height, 8, 0, nullptr), "write");
  // Loop forever: the NETSCAPE2.0 application extension, loop count 0.
  static const char kNetscape[] = "NETSCAPE2.0";
  const unsigned char loop[3] = {1, 0, 0};
  d.check(EGifPutExtensionLeader(d.gif, APPLICATION_EXT_FUNC_CODE), "write");
  d.check(EGifPutExtensionBlock(d.gif, 11, kNetscape), "write");
  d.check(EGifPutExtensionBlock(d.gif, 3, loop), "write");
  d.check(EGifPutExtensionTrailer(d.gif), "write");
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  d.previous.assign(pixels, 0);
  d.current.assign(pixels, 0);
}

GifWriter::~GifWriter() = default;
GifWriter::GifWriter(GifWriter&& other) noexcept = default;
GifWriter& GifWriter::operator=(GifWriter&& other) noexcept = default;

int GifWriter::frame_count() const { return impl_->frames; }
const std::string& GifWriter::path() const { return impl_->file.path(); }
const std::string& GifWriter::temp_path() const { return impl_->file.temp_path(); }

void GifWriter::add_frame(const Canvas& canvas) {
  Impl& d = *impl_;
  if (d.finished || d.failed) {
    throw Error("GifWriter::add_frame: '" + d.file.path() + "' is " +
                (d.finished ? "finished" : "broken by an earlier error"));
  }
  if (canvas.pixel_width() != d.width || canvas.pixel_height() != d.height) {
    throw Error("GifWriter::add_frame: the canvas is " + std::to_string(canvas.pixel_width()) +
                " x " + std::to_string(canvas.pixel_height()) + " pixels, the GIF " +
                std::to_string(d.width) + " x " + std::to_string(d.height));
  }
  // Flatten onto white (premultiplied: c + 255 - a) as 0x00RRGGBB.
  const unsigned char* data = canvas.argb32_data();
  const int stride = canvas.stride();
  for (int y = 0; y < d.height; ++y) {
    const unsigned char* row = data + static_cast<std::ptrdiff_t>(y) * stride;
    std::uint32_t* out = d.current.data() + static_cast<std::ptrdiff_t>(y) * d.width;
    for (int x = 0; x < d.width; ++x) {
      std::uint32_t p;
      std::memcpy(&p, row + static_cast<std::ptrdiff_t>(x) * 4, sizeof p);
      const std::uint32_t a = p >> 24;
      if (a != 255) {
        const std::uint32_t add = 255 - a;
        p = ((((p >> 16) & 0xffu) + add) << 16) | ((((p >> 8) & 0xffu) + add) << 8) |
            ((p & 0xffu) + add);
      }
      out[x] = p & 0xFFFFFFu;
    }
  }
  // Only the rectangle that changed since the last frame is written (the
  // rest stays: disposal "do not dispose").
  int x0 = 0;
  int y0 = 0;
  int x1 = d.width - 1;
  int y1 = d.height - 1;
  if (d.frames > 0) {
    x0 = d.width;
    y0 = d.height;
    x1 = -1;
    y1 = -1;
    for (int y = 0; y < d.height; ++y) {
      const std::uint32_t* a = d.current.data() + static_cast<std::ptrdiff_t>(y) * d.width;
      const std::uint32_t* b = d.previous.data() + static_cast<std::ptrdiff_t>(y) * d.width;
      if (std::memcmp(a, b, static_cast<std::size_t>(d.width) * sizeof *a) == 0) continue;
      int first = 0;
      while (a[first] == b[first]) ++first;
      int last = d.width - 1;
      while (a[last] == b[last]) --last;
      x0 = std::min(x0, first);
      x1 = std::max(x1, last);
      y0 = std::min(y0, y);
      y1 = y;
    }
    if (x1 < 0) {  // nothing changed: one unchanged pixel carries the delay
      x0 = x1 = 0;
      y0 = y1 = 0;
    }
  }
  d.write_frame(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
  d.previous.swap(d.current);
  ++d.frames;
}

// Writes the rectangle (x0, y0, w, h) of `current` as one GIF image, with
// its exact colours if it has at most 256, else the quantiser's 256.
void GifWriter::Impl::write_frame(int x0, int y0, int w, int h) {
  static_assert(sizeof(GifPixelType) == sizeof(std::uint8_t));
  indices.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  const std::uint32_t* origin =
      current.data() + static_cast<std::ptrdiff_t>(y0) * width + static_cast<std::ptrdiff_t>(x0);
  std::vector<GifColorType> colors;
  for (std::uint32_t c : detail::quantize(origin, w, h, width, 256, indices.data())) {
    colors.push_back({static_cast<GifByteType>(c >> 16), static_cast<GifByteType>((c >> 8) & 0xff),
                      static_cast<GifByteType>(c & 0xff)});
  }
  // GIF palettes hold 2^k entries: pad with the last colour, so that the
  // palette holds the frame's colours and no other.
  std::size_t size = 2;
  while (size < colors.size()) size *= 2;
  colors.resize(size, colors.back());

  GraphicsControlBlock control{};
  control.DisposalMode = DISPOSE_DO_NOT;
  control.UserInputFlag = false;
  control.DelayTime = delay_cs(frames, fps);
  control.TransparentColor = NO_TRANSPARENT_COLOR;
  GifByteType extension[4];
  const auto length = EGifGCBToExtension(&control, extension);
  check(EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(length), extension),
        "write");
  ColorMapObject* map = GifMakeMapObject(static_cast<int>(size), colors.data());
  if (map == nullptr) throw Error("GifWriter: out of memory");
  const int described = EGifPutImageDesc(gif, x0, y0, w, h, false, map);
  GifFreeMapObject(map);
  check(described, "write");
  for (int y = 0; y < h; ++y) {
    check(EGifPutLine(gif, indices.data() + static_cast<std::ptrdiff_t>(y) * w, w), "write");
  }
}

void GifWriter::finish() {
  Impl& d = *impl_;
  if (d.finished) throw Error("GifWriter::finish: '" + d.file.path() + "' is already finished");
  if (d.failed) {
    throw Error("GifWriter::finish: '" + d.file.path() + "' is broken by an earlier error");
  }
  if (d.frames == 0) throw Error("GifWriter::finish: no frames for '" + d.file.path() + "'");
  int error = 0;
  GifFileType* gif = std::exchange(d.gif, nullptr);
  if (EGifCloseFile(gif, &error) == GIF_ERROR) {
    d.failed = true;
    d.file.discard();
    throw Error("GifWriter: cannot write '" + d.file.path() + "': " +
                (GifErrorString(error) != nullptr ? GifErrorString(error) : "giflib error"));
  }
  d.finished = true;
  d.file.commit();
}

}  // namespace calder
