// SPDX-License-Identifier: MIT
// calder render: colour quantisation for GIF frames (internal to calder::render).
//
// A frame with at most `max_colors` colours keeps them exactly. Otherwise the
// palette comes from Wu's variance-minimising box cuts (X. Wu, "Efficient
// statistical computations for optimal color quantization", Graphics Gems II,
// 1991) refined by Lloyd's k-means iterations over the frame's distinct
// colours (S. P. Lloyd, "Least squares quantization in PCM", IEEE Trans.
// Information Theory 28(2), 1982), and every pixel takes its nearest palette
// colour (squared RGB distance). No dithering: the frames are flat shapes
// with anti-aliased edges, where dither noise costs PSNR and LZW size and
// would flicker from frame to frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace calder::detail {

// Quantises the w x h pixels at `pixels` (0x00RRGGBB, rows `stride` pixels
// apart) to at most `max_colors` (1..256) colours: the palette (0x00RRGGBB) is
// returned and pixel (x, y) gets palette index indices[y * w + x]. `indices`
// must hold w * h entries. Deterministic: the same pixels give the same bits.
std::vector<std::uint32_t> quantize(const std::uint32_t* pixels, int w, int h,
                                    std::ptrdiff_t stride, int max_colors, std::uint8_t* indices);

}  // namespace calder::detail
