// OpenEXR reader and writer, built on the OpenEXR 3.1 C++ library (Imf).
//
// Reference: "Reading and Writing OpenEXR Image Files with the IlmImf Library" (openexr.com documentation) and
// "Technical Introduction to OpenEXR" (data window vs display window, luminance/chroma images, tiled and
// multi-resolution files).
// Reading:
//   - the image is the DATA window (an offset data window such as (1,1)-(1022,574) gives a 1022 x 574 image);
//   - scanline and tiled files through Imf::InputFile, which reads level (0,0), the full resolution, of
//     mip-mapped and rip-mapped files;
//   - every channel is read as 32-bit float (half and uint are converted by the library);
//   - R, G, B (a missing one of the three reads as 0), optional A -> channels 3 or 4;
//   - luminance only (Y, no RY/BY) -> R = G = B = Y, channels 1 (or 4 with A);
//   - luminance/chroma (Y, RY, BY, chroma usually 2x2 subsampled) is decoded to RGB by Imf::RgbaInputFile, the
//     library's own reconstruction filter (half precision), channels 3 or 4;
//   - the chromaticities attribute is copied to metadata when present.
// Writing: R, G, B (+ A when channels == 4), half or float, ZIP compression, chromaticities kept. The file is
// built in memory (Imf::OStream over a byte vector) and stored by write_file_atomically: Imf::OutputFile writes its
// line-offset table from its destructor, which swallows errors, so writing to disk directly would lose them.
// The file is read from memory (Imf::IStream over the bytes read_image loaded), and every library exception is
// turned into blocklab::Error("<path>: ...").
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfChromaticities.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <Iex.h>
#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "core/atomic_write.h"
#include "core/image_io_detail.h"

namespace blocklab::image_io_detail {
namespace {

// Widest / tallest data window or tile OpenEXR may even start to read. The library allocates line and tile
// buffers from the header before our own size check could run, so its limits are set too (process-wide; blocklab
// is the only user of OpenEXR in the process). kMaxTexels still bounds width * height.
constexpr int kMaxExrDimension = 1 << 17;
constexpr int kMaxExrTileDimension = 1 << 14;

void set_openexr_limits_once() {
  static const bool done = [] {
    Imf::Header::setMaxImageSize(kMaxExrDimension, kMaxExrDimension);
    Imf::Header::setMaxTileSize(kMaxExrTileDimension, kMaxExrTileDimension);
    return true;
  }();
  (void)done;
}

// Imf::IStream over bytes already in memory. Reads past the end throw (the library turns that into its own
// "unexpected end of file" errors, which we rethrow as blocklab::Error).
class MemoryIStream final : public Imf::IStream {
 public:
  MemoryIStream(const std::string& path, const Bytes& bytes) : Imf::IStream(path.c_str()), bytes_(bytes) {}

  bool read(char c[], int n) override {
    if (n < 0 || position_ > bytes_.size() || static_cast<std::uint64_t>(n) > bytes_.size() - position_) {
      throw Iex::InputExc("unexpected end of file");
    }
    std::memcpy(c, bytes_.data() + position_, static_cast<std::size_t>(n));
    position_ += static_cast<std::uint64_t>(n);
    return position_ < bytes_.size();  // IStream contract: false once the last byte has been read
  }
  std::uint64_t tellg() override { return position_; }
  void seekg(std::uint64_t position) override { position_ = position; }  // a later read past the end throws

 private:
  const Bytes& bytes_;
  std::uint64_t position_ = 0;
};

// Imf::OStream into a growing byte vector (seekp back is used to patch the line-offset table).
class MemoryOStream final : public Imf::OStream {
 public:
  MemoryOStream(const std::string& path, Bytes& bytes) : Imf::OStream(path.c_str()), bytes_(bytes) {}

  void write(const char c[], int n) override {
    if (n < 0) throw Iex::ArgExc("negative write size");
    const std::uint64_t end = position_ + static_cast<std::uint64_t>(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + position_, c, static_cast<std::size_t>(n));
    position_ = end;
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t position) override { position_ = position; }

 private:
  Bytes& bytes_;
  std::uint64_t position_ = 0;
};

void copy_chromaticities(const Imf::Header& header, ImageMetadata& metadata) {
  if (!Imf::hasChromaticities(header)) return;
  const Imf::Chromaticities& c = Imf::chromaticities(header);
  metadata.chromaticities = std::array<float, 8>{c.red.x, c.red.y, c.green.x, c.green.y,
                                                 c.blue.x, c.blue.y, c.white.x, c.white.y};
}

struct DataWindowSize {
  int width;
  int height;
};

DataWindowSize checked_size(const std::string& path, const Imath::Box2i& window) {
  // int64 arithmetic: max - min + 1 overflows int for a corrupt window.
  const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
  const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
  check_image_size(path, width, height);
  return {static_cast<int>(width), static_cast<int>(height)};
}

// Luminance/chroma files: the library's RgbaInputFile reconstructs RGB (including 2x2-subsampled chroma).
Image read_luminance_chroma(const std::string& path, const Bytes& bytes) {
  MemoryIStream stream(path, bytes);
  Imf::RgbaInputFile file(stream);
  const DataWindowSize size = checked_size(path, file.dataWindow());
  const bool has_alpha = (file.channels() & Imf::WRITE_A) != 0;
  std::vector<Imf::Rgba> rgba(static_cast<std::size_t>(size.width) * static_cast<std::size_t>(size.height));
  // The frame buffer is addressed in data-window coordinates: base = &rgba[0] - (min.x + min.y * width).
  // Computed in integers so no out-of-range pointer arithmetic happens in our code.
  const Imath::Box2i& window = file.dataWindow();
  const std::intptr_t origin_offset =
      (static_cast<std::intptr_t>(window.min.x) + static_cast<std::intptr_t>(window.min.y) * size.width) *
      static_cast<std::intptr_t>(sizeof(Imf::Rgba));
  file.setFrameBuffer(reinterpret_cast<Imf::Rgba*>(reinterpret_cast<std::intptr_t>(rgba.data()) - origin_offset), 1,
                      static_cast<std::size_t>(size.width));
  file.readPixels(window.min.y, window.max.y);

  Image image(size.width, size.height, has_alpha ? 4 : 3);
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    image.pixels[4 * i + 0] = static_cast<float>(rgba[i].r);
    image.pixels[4 * i + 1] = static_cast<float>(rgba[i].g);
    image.pixels[4 * i + 2] = static_cast<float>(rgba[i].b);
    image.pixels[4 * i + 3] = has_alpha ? static_cast<float>(rgba[i].a) : 1.0f;
  }
  image.metadata.pixel_type = "half";  // RgbaInputFile works in half
  copy_chromaticities(file.header(), image.metadata);
  return image;
}

std::string channel_names(const Imf::ChannelList& channels) {
  std::string names;
  for (auto it = channels.begin(); it != channels.end(); ++it) names += (names.empty() ? "" : ", ") + std::string(it.name());
  return names.empty() ? "none" : names;
}

Image read_exr_unchecked(const std::string& path, const Bytes& bytes) {
  set_openexr_limits_once();
  MemoryIStream stream(path, bytes);
  Imf::InputFile file(stream);
  const Imf::Header& header = file.header();
  const Imf::ChannelList& channels = header.channels();

  const bool has_rgb = channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
  const bool has_luminance = channels.findChannel("Y") != nullptr;
  const bool has_chroma = channels.findChannel("RY") || channels.findChannel("BY");
  if (!has_rgb && has_luminance && has_chroma) return read_luminance_chroma(path, bytes);
  if (!has_rgb && !has_luminance) {
    fail(path, "OpenEXR file has no R, G, B or Y channel (channels: " + channel_names(channels) + ")");
  }
  const bool has_alpha = channels.findChannel("A") != nullptr;

  // Which file channel lands in which of the four floats of a texel.
  std::vector<std::pair<const char*, int>> slots;
  if (has_rgb) {
    slots = {{"R", 0}, {"G", 1}, {"B", 2}};
  } else {
    slots = {{"Y", 0}};
  }
  if (has_alpha) slots.push_back({"A", 3});

  bool all_half = true;
  for (const auto& slot : slots) {
    const Imf::Channel* channel = channels.findChannel(slot.first);
    if (!channel) continue;  // a missing R, G or B reads as the slice fill value 0
    if (channel->xSampling != 1 || channel->ySampling != 1) {
      fail(path, std::string("OpenEXR channel ") + slot.first + " is subsampled (" + std::to_string(channel->xSampling) +
                     "x" + std::to_string(channel->ySampling) + "); only luminance/chroma files may subsample");
    }
    if (channel->type != Imf::HALF) all_half = false;
  }

  const Imath::Box2i& window = header.dataWindow();
  const DataWindowSize size = checked_size(path, window);
  // The header alone may claim up to kMaxTexels (2 GiB of floats) while the file holds a few bytes of chunks, so
  // the pixels are only reserved (address space, no memory touched) and grow strip by strip as chunks decode: a
  // file that fails at its first bad or missing chunk never fills gigabytes first. A strip of 256 rows is a
  // multiple of every scanline compression's chunk height (1, 16, 32, 256), so no chunk is decoded twice.
  Image image;
  image.width = size.width;
  image.height = size.height;
  image.channels = has_rgb ? (has_alpha ? 4 : 3) : (has_alpha ? 4 : 1);
  const std::size_t row_floats = 4 * static_cast<std::size_t>(size.width);
  image.pixels.reserve(row_floats * static_cast<std::size_t>(size.height));   // data() is stable from here on
  Imf::FrameBuffer frame_buffer;
  const std::size_t x_stride = 4 * sizeof(float);
  const std::size_t y_stride = x_stride * static_cast<std::size_t>(size.width);
  for (const auto& slot : slots) {
    // Slice::Make computes the data-window-relative base pointer without overflow.
    frame_buffer.insert(slot.first, Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + slot.second,
                                                      window, x_stride, y_stride, 1, 1, 0.0));
  }
  file.setFrameBuffer(frame_buffer);
  constexpr int kStripRows = 256;
  for (int first_row = 0; first_row < size.height; first_row += kStripRows) {
    const int rows = std::min(kStripRows, size.height - first_row);
    const std::size_t begin = image.pixels.size();
    image.pixels.resize(begin + row_floats * static_cast<std::size_t>(rows), 0.0f);
    for (std::size_t i = begin + 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;   // alpha when absent
    file.readPixels(window.min.y + first_row, window.min.y + first_row + rows - 1);
  }

  if (!has_rgb) {  // luminance only: R = G = B = Y
    for (std::size_t i = 0; i < image.texel_count(); ++i) image.pixels[4 * i + 1] = image.pixels[4 * i + 2] = image.pixels[4 * i];
  }
  image.metadata.pixel_type = all_half ? "half" : "float";  // uint channels are reported as float (converted)
  copy_chromaticities(header, image.metadata);
  return image;
}

}  // namespace

Image read_exr(const std::string& path, const Bytes& bytes) {
  Image image;
  try {
    image = read_exr_unchecked(path, bytes);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    fail(path, std::string("corrupt or unsupported OpenEXR file (") + e.what() + ")");
  } catch (...) {
    fail(path, "corrupt or unsupported OpenEXR file (unknown OpenEXR error)");
  }
  image.metadata.container = "exr";
  image.metadata.is_hdr = true;
  return image;
}

void write_exr(const std::string& path, const Image& image, ExrPixelType pixel_type) {
  Bytes encoded;
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    if (image.metadata.chromaticities) {
      const auto& c = *image.metadata.chromaticities;
      Imf::addChromaticities(header, Imf::Chromaticities(Imath::V2f(c[0], c[1]), Imath::V2f(c[2], c[3]),
                                                         Imath::V2f(c[4], c[5]), Imath::V2f(c[6], c[7])));
    }
    const Imf::PixelType type = pixel_type == ExrPixelType::half ? Imf::HALF : Imf::FLOAT;
    const int written_channels = image.channels == 4 ? 4 : 3;  // luminance-only images are written as R = G = B
    static const char* const kNames[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < written_channels; ++c) header.channels().insert(kNames[c], Imf::Channel(type));

    Imf::FrameBuffer frame_buffer;
    std::vector<half> half_pixels;
    if (type == Imf::HALF) {
      // float -> half rounds to nearest even; values beyond the half range become +-Inf (Imath semantics).
      half_pixels.assign(image.pixels.begin(), image.pixels.end());
      const std::size_t stride = 4 * sizeof(half);
      for (int c = 0; c < written_channels; ++c) {
        frame_buffer.insert(kNames[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(&half_pixels[c]), stride,
                                                  stride * static_cast<std::size_t>(image.width)));
      }
    } else {
      const std::size_t stride = 4 * sizeof(float);
      for (int c = 0; c < written_channels; ++c) {
        // OutputFile only reads through the slice; Slice's pointer is non-const by API design.
        char* base = reinterpret_cast<char*>(const_cast<float*>(&image.pixels[static_cast<std::size_t>(c)]));
        frame_buffer.insert(kNames[c], Imf::Slice(Imf::FLOAT, base, stride, stride * static_cast<std::size_t>(image.width)));
      }
    }
    MemoryOStream stream(path, encoded);
    {
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(frame_buffer);
      file.writePixels(image.height);
    }  // the destructor writes the line-offset table into `encoded`
  } catch (const std::exception& e) {
    fail(path, std::string("cannot encode OpenEXR file (") + e.what() + ")");
  }
  write_file_atomically(path, encoded);
}

}  // namespace blocklab::image_io_detail

namespace blocklab {

HalfConversionLoss half_conversion_loss(const Image& image) {
  HalfConversionLoss loss;
  const std::size_t written_channels = image.channels == 4 ? 4 : 3;   // as write_exr writes them
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    for (std::size_t c = 0; c < written_channels; ++c) {
      const float value = image.pixels[4 * i + c];
      const half rounded(value);   // the conversion write_exr uses
      if (rounded.isInfinity() && std::isfinite(value)) ++loss.overflowed;
      if (rounded.isZero() && value != 0.0f) ++loss.flushed_to_zero;
    }
  }
  return loss;
}

}  // namespace blocklab
