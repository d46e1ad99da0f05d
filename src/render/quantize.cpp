// SPDX-License-Identifier: MIT
// calder render: colour quantisation for GIF frames. The method and its
// sources are described in quantize.hpp; the code is calder's own.
#include "quantize.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "calder/error.hpp"

namespace calder::detail {

namespace {

int red(std::uint32_t c) { return static_cast<int>((c >> 16) & 0xffu); }
int green(std::uint32_t c) { return static_cast<int>((c >> 8) & 0xffu); }
int blue(std::uint32_t c) { return static_cast<int>(c & 0xffu); }

// Colours of a frame mapped to palette indices while they number at most
// 256: open addressing in a table four times that size.
class ExactPalette {
 public:
  explicit ExactPalette(std::size_t limit) : limit_(limit) { keys_.fill(kEmpty); }

  // The colour's index, adding it; -1 once there would be more than the limit.
  int index_of(std::uint32_t color) {
    std::uint32_t slot = (color * 0x9E3779B1u) >> (32 - kBits);
    while (true) {
      if (keys_[slot] == color) return values_[slot];
      if (keys_[slot] == kEmpty) {
        if (colors_.size() == limit_) return -1;
        keys_[slot] = color;
        values_[slot] = static_cast<std::uint8_t>(colors_.size());
        colors_.push_back(color);
        return values_[slot];
      }
      slot = (slot + 1) & (kSize - 1);
    }
  }
  [[nodiscard]] std::vector<std::uint32_t>& colors() { return colors_; }

 private:
  static constexpr int kBits = 10;
  static constexpr std::uint32_t kSize = 1u << kBits;
  static constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;  // not a 24-bit colour
  std::size_t limit_;
  std::array<std::uint32_t, kSize> keys_{};
  std::array<std::uint8_t, kSize> values_{};
  std::vector<std::uint32_t> colors_;
};

// Maps the pixels to their exact colours' indices if there are at most
// `limit` (false otherwise).
bool map_exact(const std::uint32_t* pixels, int w, int h, std::ptrdiff_t stride, int limit,
               std::uint8_t* indices, std::vector<std::uint32_t>& palette) {
  ExactPalette exact(static_cast<std::size_t>(limit));
  std::uint32_t last_color = 0xFFFFFFFFu;
  int last_index = 0;
  for (int y = 0; y < h; ++y) {
    const std::uint32_t* row = pixels + y * stride;
    std::uint8_t* out = indices + static_cast<std::ptrdiff_t>(y) * w;
    for (int x = 0; x < w; ++x) {
      if (row[x] != last_color) {
        last_index = exact.index_of(row[x]);
        if (last_index < 0) return false;
        last_color = row[x];
      }
      out[x] = static_cast<std::uint8_t>(last_index);
    }
  }
  palette = std::move(exact.colors());
  return true;
}

// A frame's distinct colours, ascending, with how many pixels have each.
struct ColorCounts {
  std::vector<std::uint32_t> colors;
  std::vector<double> counts;
};

ColorCounts count_colors(const std::uint32_t* pixels, int w, int h, std::ptrdiff_t stride) {
  std::vector<std::uint32_t> all;
  all.reserve(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y) all.insert(all.end(), pixels + y * stride, pixels + y * stride + w);
  std::sort(all.begin(), all.end());
  ColorCounts result;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i + 1;
    while (j < all.size() && all[j] == all[i]) ++j;
    result.colors.push_back(all[i]);
    result.counts.push_back(static_cast<double>(j - i));
    i = j;
  }
  return result;
}

using Rgb = std::array<double, 3>;

double distance2(const Rgb& a, const Rgb& b) {
  const double dr = a[0] - b[0];
  const double dg = a[1] - b[1];
  const double db = a[2] - b[2];
  return dr * dr + dg * dg + db * db;
}

Rgb rgb_of(std::uint32_t c) {
  return {static_cast<double>(red(c)), static_cast<double>(green(c)), static_cast<double>(blue(c))};
}

// Wu's quantiser: a 32 x 32 x 32 histogram (5 bits a channel) of the pixel
// count, the colour sums and the sum of squares, summed into cumulative
// moments so that any box's totals take eight look-ups; the box of largest
// variance is cut where the two halves' summed variances are least.
class WuQuantizer {
 public:
  explicit WuQuantizer(const ColorCounts& counts)
      : weight_(kCells), sum_(kCells), squares_(kCells) {
    for (std::size_t i = 0; i < counts.colors.size(); ++i) {
      const std::uint32_t c = counts.colors[i];
      const std::size_t cell = index((red(c) >> 3) + 1, (green(c) >> 3) + 1, (blue(c) >> 3) + 1);
      const double n = counts.counts[i];
      const Rgb v = rgb_of(c);
      weight_[cell] += n;
      for (int k = 0; k < 3; ++k)
        sum_[cell][static_cast<std::size_t>(k)] += n * v[static_cast<std::size_t>(k)];
      squares_[cell] += n * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    accumulate();
  }

  // The means of at most `max_colors` boxes.
  std::vector<Rgb> palette(int max_colors) {
    std::vector<Box> boxes{Box{}};
    std::vector<double> variances{variance(boxes[0])};
    while (static_cast<int>(boxes.size()) < max_colors) {
      const auto worst = std::max_element(variances.begin(), variances.end());
      if (*worst <= 0.0) break;
      const auto which = static_cast<std::size_t>(worst - variances.begin());
      Box second;
      if (!cut(boxes[which], second)) {
        variances[which] = 0.0;
        continue;
      }
      boxes.push_back(second);
      variances[which] = variance(boxes[which]);
      variances.push_back(variance(second));
    }
    std::vector<Rgb> means;
    for (const Box& box : boxes) {
      const double n = volume(box, weight_);
      if (n <= 0.0) continue;
      const Rgb s = volume_rgb(box);
      means.push_back({s[0] / n, s[1] / n, s[2] / n});
    }
    return means;
  }

 private:
  static constexpr int kSide = 33;  // 32 bins and a zero row in front
  static constexpr std::size_t kCells = static_cast<std::size_t>(kSide * kSide * kSide);

  // The cells (lower, upper] on each axis.
  struct Box {
    std::array<int, 3> lower{0, 0, 0};
    std::array<int, 3> upper{kSide - 1, kSide - 1, kSide - 1};
  };

  static std::size_t index(int r, int g, int b) {
    return static_cast<std::size_t>((r * kSide + g) * kSide + b);
  }

  // Prefix sums along each axis in turn make every cell the total of the
  // box from the origin to it.
  void accumulate() {
    for (int axis = 0; axis < 3; ++axis) {
      for (int r = 1; r < kSide; ++r) {
        for (int g = 1; g < kSide; ++g) {
          for (int b = 1; b < kSide; ++b) {
            const std::size_t here = index(r, g, b);
            const std::size_t before = axis == 0   ? index(r - 1, g, b)
                                       : axis == 1 ? index(r, g - 1, b)
                                                   : index(r, g, b - 1);
            weight_[here] += weight_[before];
            for (std::size_t k = 0; k < 3; ++k) sum_[here][k] += sum_[before][k];
            squares_[here] += squares_[before];
          }
        }
      }
    }
  }

  // A box's total of a cumulative moment, by inclusion and exclusion.
  template <typename Moment>
  static Moment corner_sum(const Box& box, const std::vector<Moment>& m) {
    const auto& lo = box.lower;
    const auto& hi = box.upper;
    auto at = [&](int r, int g, int b) { return m[index(r, g, b)]; };
    if constexpr (std::is_same_v<Moment, Rgb>) {
      Rgb total{};
      for (std::size_t k = 0; k < 3; ++k) {
        total[k] = at(hi[0], hi[1], hi[2])[k] - at(hi[0], hi[1], lo[2])[k] -
                   at(hi[0], lo[1], hi[2])[k] + at(hi[0], lo[1], lo[2])[k] -
                   at(lo[0], hi[1], hi[2])[k] + at(lo[0], hi[1], lo[2])[k] +
                   at(lo[0], lo[1], hi[2])[k] - at(lo[0], lo[1], lo[2])[k];
      }
      return total;
    } else {
      return at(hi[0], hi[1], hi[2]) - at(hi[0], hi[1], lo[2]) - at(hi[0], lo[1], hi[2]) +
             at(hi[0], lo[1], lo[2]) - at(lo[0], hi[1], hi[2]) + at(lo[0], hi[1], lo[2]) +
             at(lo[0], lo[1], hi[2]) - at(lo[0], lo[1], lo[2]);
    }
  }
  [[nodiscard]] double volume(const Box& box, const std::vector<double>& m) const {
    return corner_sum(box, m);
  }
  [[nodiscard]] Rgb volume_rgb(const Box& box) const { return corner_sum(box, sum_); }

  // Sum of squared distances to the box's mean; zero for a single cell,
  // which cannot be cut.
  [[nodiscard]] double variance(const Box& box) const {
    int cells = 1;
    for (std::size_t k = 0; k < 3; ++k) cells *= box.upper[k] - box.lower[k];
    if (cells <= 1) return 0.0;
    const double n = volume(box, weight_);
    if (n <= 0.0) return 0.0;
    const Rgb s = volume_rgb(box);
    return volume(box, squares_) - (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / n;
  }

  // Cuts `box` in two where sum |S|^2 / n over the halves is largest (their
  // summed variances least); false if no cut leaves both halves non-empty.
  bool cut(Box& box, Box& second) const {
    const double whole_n = volume(box, weight_);
    const Rgb whole_s = volume_rgb(box);
    double best = -1.0;
    int best_axis = -1;
    int best_at = 0;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      for (int at = box.lower[axis] + 1; at < box.upper[axis]; ++at) {
        Box half = box;
        half.upper[axis] = at;
        const double n = volume(half, weight_);
        if (n <= 0.0 || n >= whole_n) continue;
        const Rgb s = volume_rgb(half);
        const Rgb rest{whole_s[0] - s[0], whole_s[1] - s[1], whole_s[2] - s[2]};
        const double score =
            (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / n +
            (rest[0] * rest[0] + rest[1] * rest[1] + rest[2] * rest[2]) / (whole_n - n);
        if (score > best) {
          best = score;
          best_axis = static_cast<int>(axis);
          best_at = at;
        }
      }
    }
    if (best_axis < 0) return false;
    const auto axis = static_cast<std::size_t>(best_axis);
    second = box;
    box.upper[axis] = best_at;
    second.lower[axis] = best_at;
    return true;
  }

  std::vector<double> weight_;
  std::vector<Rgb> sum_;
  std::vector<double> squares_;
};

// Nearest palette colour by squared RGB distance. The palette is sorted by
// r + g + b, and the search walks outwards from the query's sum: since
// (d_r + d_g + d_b)^2 <= 3 |d|^2, it stops once the sums differ by more than
// sqrt(3) times the best distance found.
class NearestColor {
 public:
  explicit NearestColor(const std::vector<Rgb>& palette) : palette_(palette) {
    order_.resize(palette.size());
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    std::stable_sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) {
      return key(palette[a]) < key(palette[b]);
    });
    for (std::size_t i : order_) keys_.push_back(key(palette[i]));
  }

  [[nodiscard]] std::size_t find(const Rgb& c) const {
    const double k = key(c);
    const auto start = static_cast<std::ptrdiff_t>(std::lower_bound(keys_.begin(), keys_.end(), k) -
                                                   keys_.begin());
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_index = order_.empty() ? 0 : order_[0];
    auto consider = [&](std::ptrdiff_t at) {
      const double dk = keys_[static_cast<std::size_t>(at)] - k;
      if (dk * dk > 3.0 * best) return false;
      const std::size_t i = order_[static_cast<std::size_t>(at)];
      const double d = distance2(palette_[i], c);
      // Ties go to the lower palette index, whichever side is walked first.
      if (d < best || (d == best && i < best_index)) {
        best = d;
        best_index = i;
      }
      return true;
    };
    const auto size = static_cast<std::ptrdiff_t>(keys_.size());
    for (std::ptrdiff_t up = start; up < size && consider(up); ++up) {
    }
    for (std::ptrdiff_t down = start - 1; down >= 0 && consider(down); --down) {
    }
    return best_index;
  }

 private:
  static double key(const Rgb& c) { return c[0] + c[1] + c[2]; }
  const std::vector<Rgb>& palette_;
  std::vector<std::size_t> order_;
  std::vector<double> keys_;
};

// Wu's boxes cannot split a histogram cell, so a frame with a few hundred
// colours may get fewer boxes than palette entries: the free entries start
// at the colours that the boxes' means serve worst (pixel count times
// squared distance), for k-means to settle.
void fill_free_entries(const ColorCounts& counts, std::size_t max_colors,
                       std::vector<Rgb>& centres) {
  if (centres.size() >= max_colors) return;
  std::vector<std::pair<double, std::size_t>> worst;  // (-error, colour), for an ascending sort
  {
    const NearestColor nearest(centres);
    for (std::size_t i = 0; i < counts.colors.size(); ++i) {
      const Rgb c = rgb_of(counts.colors[i]);
      const double error = counts.counts[i] * distance2(centres[nearest.find(c)], c);
      if (error > 0.0) worst.emplace_back(-error, i);
    }
  }
  const std::size_t take = std::min(max_colors - centres.size(), worst.size());
  std::partial_sort(worst.begin(), worst.begin() + static_cast<std::ptrdiff_t>(take), worst.end());
  for (std::size_t k = 0; k < take; ++k) centres.push_back(rgb_of(counts.colors[worst[k].second]));
}

// Lloyd's iterations: each distinct colour joins its nearest centre, each
// centre moves to its members' weighted mean (an empty one stays), until no
// colour changes centre.
void refine(const ColorCounts& counts, std::vector<Rgb>& centres) {
  constexpr int kMaxIterations = 8;
  std::vector<std::size_t> member(counts.colors.size(), centres.size());
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    bool changed = false;
    {
      const NearestColor nearest(centres);
      for (std::size_t i = 0; i < counts.colors.size(); ++i) {
        const std::size_t j = nearest.find(rgb_of(counts.colors[i]));
        changed = changed || j != member[i];
        member[i] = j;
      }
    }
    if (!changed) break;
    std::vector<Rgb> sums(centres.size(), Rgb{});
    std::vector<double> weights(centres.size(), 0.0);
    for (std::size_t i = 0; i < counts.colors.size(); ++i) {
      const Rgb c = rgb_of(counts.colors[i]);
      const double n = counts.counts[i];
      for (std::size_t k = 0; k < 3; ++k) sums[member[i]][k] += n * c[k];
      weights[member[i]] += n;
    }
    for (std::size_t j = 0; j < centres.size(); ++j) {
      if (weights[j] <= 0.0) continue;
      for (std::size_t k = 0; k < 3; ++k) centres[j][k] = sums[j][k] / weights[j];
    }
  }
}

std::uint8_t channel(double v) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

}  // namespace

std::vector<std::uint32_t> quantize(const std::uint32_t* pixels, int w, int h,
                                    std::ptrdiff_t stride, int max_colors, std::uint8_t* indices) {
  if (max_colors < 1 || max_colors > 256 || w < 1 || h < 1 || stride < w) {
    throw Error("quantize: needs 1..256 colours and a non-empty image (got " +
                std::to_string(max_colors) + " colours, " + std::to_string(w) + " x " +
                std::to_string(h) + " pixels, stride " + std::to_string(stride) + ")");
  }
  std::vector<std::uint32_t> palette;
  if (map_exact(pixels, w, h, stride, max_colors, indices, palette)) return palette;

  const ColorCounts counts = count_colors(pixels, w, h, stride);
  std::vector<Rgb> centres = WuQuantizer(counts).palette(max_colors);
  fill_free_entries(counts, static_cast<std::size_t>(max_colors), centres);
  refine(counts, centres);
  std::vector<Rgb> rounded;
  for (const Rgb& c : centres) {
    palette.push_back((std::uint32_t{channel(c[0])} << 16) | (std::uint32_t{channel(c[1])} << 8) |
                      channel(c[2]));
    rounded.push_back(rgb_of(palette.back()));
  }
  // Each distinct colour's index in the final (rounded) palette, then each
  // pixel's by looking its colour up.
  const NearestColor nearest(rounded);
  std::vector<std::uint8_t> color_index(counts.colors.size());
  for (std::size_t i = 0; i < counts.colors.size(); ++i) {
    color_index[i] = static_cast<std::uint8_t>(nearest.find(rgb_of(counts.colors[i])));
  }
  std::uint32_t last_color = 0xFFFFFFFFu;
  std::uint8_t last_index = 0;
  for (int y = 0; y < h; ++y) {
    const std::uint32_t* row = pixels + y * stride;
    std::uint8_t* out = indices + static_cast<std::ptrdiff_t>(y) * w;
    for (int x = 0; x < w; ++x) {
      if (row[x] != last_color) {
        last_color = row[x];
        const auto at = std::lower_bound(counts.colors.begin(), counts.colors.end(), last_color);
        last_index = color_index[static_cast<std::size_t>(at - counts.colors.begin())];
      }
      out[x] = last_index;
    }
  }
  return palette;
}

}  // namespace calder::detail
