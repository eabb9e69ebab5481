// PNG reader and writer on libpng 1.6.
//
// Reference: PNG Specification (ISO/IEC 15948, W3C 2nd ed.) and the libpng 1.6 manual (libpng-manual.txt):
//   - reading: 1/2/4/8/16-bit grey, grey + alpha, RGB, RGBA and palette images; palette -> RGB, tRNS -> alpha,
//     low-bit grey expanded to 8 bits (so value = code / (2^bits - 1)), interlaced images de-interlaced;
//     values are code / 255 or code / 65535, NO sRGB/gamma decoding (SPECS.md section 1d: LDR PSNR is on codes);
//   - channels: grey -> 1, RGB -> 3, anything with alpha (grey + alpha, RGBA, palette or grey/RGB with tRNS) -> 4;
//   - writing (encoded in memory, stored by write_file_atomically): 8 or 16 bit, grey (channels 1), RGB (3) or RGBA (4); values clamped to [0, 1] and rounded to the
//     nearest code.
// Error handling: libpng reports errors by longjmp to a setjmp point (libpng manual, "Setting up error handling").
// The functions that call setjmp (decode_png / encode_png) therefore hold only plain C data: no C++ object with a
// destructor lives in a frame that longjmp crosses. C++ containers live in the callers, which run after the
// setjmp function has returned. A failure comes back as a message and becomes blocklab::Error("<path>: ...").
#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/atomic_write.h"
#include "core/image_io_detail.h"

namespace blocklab::image_io_detail {
namespace {

// Plain-data state shared with libpng callbacks; it is the only thing that survives a longjmp.
struct PngDecodeState {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t position;
  char message[256];
  std::uint64_t max_texels;
  // Results (pixels is malloc'ed; the caller frees it).
  std::uint8_t* pixels;
  png_bytep* rows;
  png_uint_32 width;
  png_uint_32 height;
  int channels;        // 1..4 after the transforms below
  int bit_depth;       // 8 or 16 after the transforms below
};

void record_message(char* destination, const char* text) {
  std::snprintf(destination, 256, "%s", text ? text : "unknown libpng error");
}

extern "C" void on_png_decode_error(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngDecodeState*>(png_get_error_ptr(png));
  record_message(state->message, message);
  png_longjmp(png, 1);
}

extern "C" void on_png_warning(png_structp, png_const_charp) {}  // warnings (bad ancillary chunks) are ignored

extern "C" void read_from_memory(png_structp png, png_bytep destination, png_size_t length) {
  auto* state = static_cast<PngDecodeState*>(png_get_io_ptr(png));
  if (length > state->size - state->position) png_error(png, "truncated PNG data");
  std::memcpy(destination, state->data + state->position, length);
  state->position += length;
}

// Decodes into state->pixels. Returns true on success; on failure state->message says why and nothing is
// left allocated. Contains setjmp: plain C data only (see file header).
bool decode_png(PngDecodeState* state) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, state, on_png_decode_error, on_png_warning);
  if (!png) {
    record_message(state->message, "cannot create libpng read struct");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    record_message(state->message, "cannot create libpng info struct");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    // Reached by longjmp from on_png_decode_error. state lives in the caller's frame, so its fields are current.
    png_destroy_read_struct(&png, &info, nullptr);
    std::free(state->rows);
    std::free(state->pixels);
    state->rows = nullptr;
    state->pixels = nullptr;
    return false;
  }
  png_set_read_fn(png, state, read_from_memory);
  png_read_info(png, info);

  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, color_type = 0, interlace = 0;
  png_get_IHDR(png, info, &width, &height, &bit_depth, &color_type, &interlace, nullptr, nullptr);
  if (static_cast<std::uint64_t>(width) * height > state->max_texels) png_error(png, "image exceeds the texel limit");
  // Deflate cannot compress better than about 1032:1, so the filtered raw rows (one filter byte per row) can be
  // at most ~1032x the file size. A header that claims more is corrupt: reject before allocating.
  const std::uint64_t bits_per_pixel = static_cast<std::uint64_t>(png_get_channels(png, info)) * bit_depth;
  const std::uint64_t raw_bytes = (1 + (bits_per_pixel * width + 7) / 8) * static_cast<std::uint64_t>(height);
  if (raw_bytes / 1032 > state->size) png_error(png, "image size is impossible for the file length");

  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);

  const int channels = png_get_channels(png, info);
  const int out_depth = png_get_bit_depth(png, info);
  const png_size_t row_bytes = png_get_rowbytes(png, info);
  if ((out_depth != 8 && out_depth != 16) || channels < 1 || channels > 4 ||
      row_bytes != static_cast<png_size_t>(width) * channels * (out_depth / 8)) {
    png_error(png, "unexpected PNG layout after expansion");
  }
  state->pixels = static_cast<std::uint8_t*>(std::malloc(row_bytes * height));
  state->rows = static_cast<png_bytep*>(std::malloc(sizeof(png_bytep) * height));
  if (!state->pixels || !state->rows) png_error(png, "out of memory");
  for (png_uint_32 y = 0; y < height; ++y) state->rows[y] = state->pixels + static_cast<std::size_t>(y) * row_bytes;
  png_read_image(png, state->rows);
  // Reading up to IEND makes a file cut after its image data an error too (a PNG must end with IEND).
  png_read_end(png, nullptr);

  png_destroy_read_struct(&png, &info, nullptr);
  std::free(state->rows);
  state->rows = nullptr;
  state->width = width;
  state->height = height;
  state->channels = channels;
  state->bit_depth = out_depth;
  return true;
}

// The encoded file grows in a malloc'ed buffer (plain C data: it survives a longjmp; the caller frees it).
struct PngEncodeState {
  std::uint8_t* data;
  std::size_t size;
  std::size_t capacity;
  char message[256];
};

extern "C" void on_png_encode_write(png_structp png, png_bytep bytes, png_size_t length) {
  auto* state = static_cast<PngEncodeState*>(png_get_io_ptr(png));
  if (length > state->capacity - state->size) {
    std::size_t capacity = state->capacity == 0 ? 4096 : state->capacity;
    while (length > capacity - state->size) {
      if (capacity > SIZE_MAX / 2) png_error(png, "encoded PNG too large");
      capacity *= 2;
    }
    void* grown = std::realloc(state->data, capacity);
    if (!grown) png_error(png, "out of memory while encoding");
    state->data = static_cast<std::uint8_t*>(grown);
    state->capacity = capacity;
  }
  std::memcpy(state->data + state->size, bytes, length);
  state->size += length;
}

extern "C" void on_png_encode_flush(png_structp) {}

extern "C" void on_png_encode_error(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngEncodeState*>(png_get_error_ptr(png));
  record_message(state->message, message);
  png_longjmp(png, 1);
}

// Encodes `rows` (already in PNG byte order) into state->data. Contains setjmp: plain C data only.
bool encode_png(PngEncodeState* state, png_bytep* rows, png_uint_32 width, png_uint_32 height, int color_type,
                int bit_depth) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, state, on_png_encode_error, on_png_warning);
  if (!png) {
    record_message(state->message, "cannot create libpng write struct");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    record_message(state->message, "cannot create libpng info struct");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, state, on_png_encode_write, on_png_encode_flush);
  png_set_IHDR(png, info, width, height, bit_depth, color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

Image read_png(const std::string& path, const Bytes& bytes) {
  PngDecodeState state{};
  state.data = bytes.data();
  state.size = bytes.size();
  state.max_texels = kMaxTexels;
  if (!decode_png(&state)) fail(path, std::string("corrupt or unsupported PNG (") + state.message + ")");
  std::unique_ptr<std::uint8_t, void (*)(void*)> pixels(state.pixels, &std::free);

  const int width = static_cast<int>(state.width);
  const int height = static_cast<int>(state.height);
  const bool has_alpha = state.channels == 2 || state.channels == 4;
  const bool is_grey = state.channels <= 2;
  Image image(width, height, has_alpha ? 4 : (is_grey ? 1 : 3));
  const float max_code = state.bit_depth == 16 ? 65535.0f : 255.0f;
  const std::size_t sample_bytes = static_cast<std::size_t>(state.bit_depth / 8);
  const std::uint8_t* in = pixels.get();
  auto sample = [&](std::size_t index) -> float {
    const std::uint8_t* p = in + index * sample_bytes;
    const unsigned code = sample_bytes == 2 ? (unsigned{p[0]} << 8 | p[1]) : p[0];  // PNG 16-bit is big-endian
    return static_cast<float>(code) / max_code;
  };
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    const std::size_t first = i * static_cast<std::size_t>(state.channels);
    float* texel = &image.pixels[4 * i];
    if (is_grey) {
      texel[0] = texel[1] = texel[2] = sample(first);
      texel[3] = has_alpha ? sample(first + 1) : 1.0f;
    } else {
      texel[0] = sample(first);
      texel[1] = sample(first + 1);
      texel[2] = sample(first + 2);
      texel[3] = has_alpha ? sample(first + 3) : 1.0f;
    }
  }
  image.metadata.container = "png";
  image.metadata.pixel_type = state.bit_depth == 16 ? "uint16" : "uint8";
  image.metadata.is_hdr = false;
  return image;
}

void write_png(const std::string& path, const Image& image, int bits) {
  const int channels = image.channels;  // 1 grey, 3 RGB, 4 RGBA
  const int color_type = channels == 1 ? PNG_COLOR_TYPE_GRAY : (channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGBA);
  const std::size_t sample_bytes = bits == 16 ? 2 : 1;
  const double max_code = bits == 16 ? 65535.0 : 255.0;
  const std::size_t row_bytes = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(channels) * sample_bytes;
  Bytes encoded(row_bytes * static_cast<std::size_t>(image.height));
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    std::uint8_t* out = &encoded[static_cast<std::size_t>(y) * row_bytes];
    rows[static_cast<std::size_t>(y)] = out;
    for (int x = 0; x < image.width; ++x) {
      const float* texel = image.texel(x, y);
      for (int c = 0; c < channels; ++c) {
        const float value = texel[channels == 4 ? c : (channels == 1 ? 0 : c)];
        // Clamp to [0, 1] (NaN -> 0), then round to the nearest code (halves round up).
        const double clamped = std::isnan(value) ? 0.0 : std::min(1.0, std::max(0.0, static_cast<double>(value)));
        const unsigned code = static_cast<unsigned>(std::floor(clamped * max_code + 0.5));
        if (sample_bytes == 2) {
          *out++ = static_cast<std::uint8_t>(code >> 8);  // big-endian, as PNG stores 16-bit samples
          *out++ = static_cast<std::uint8_t>(code & 0xff);
        } else {
          *out++ = static_cast<std::uint8_t>(code);
        }
      }
    }
  }

  PngEncodeState state{};
  const bool ok = encode_png(&state, rows.data(), static_cast<png_uint_32>(image.width),
                             static_cast<png_uint_32>(image.height), color_type, bits);
  std::unique_ptr<std::uint8_t, void (*)(void*)> file_bytes(state.data, &std::free);
  if (!ok) fail(path, std::string("cannot encode PNG (") + state.message + ")");
  write_file_atomically(path, file_bytes.get(), state.size);
}

}  // namespace blocklab::image_io_detail
