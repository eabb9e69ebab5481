// YCoCg-R (Malvar & Sullivan 2003): bit-exact round trip of every 8-bit RGB triple, channel ranges (Y N bits,
// Co/Cg N + 1 bits signed), known values, and higher bit depths.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "core/color_spaces.h"

namespace blocklab {
namespace {

TEST(YCoCgRColorSpace, RoundTripsEvery8BitRgbTripleBitExactlyWithinItsChannelRanges) {
  for (std::int32_t red = 0; red < 256; ++red)
    for (std::int32_t green = 0; green < 256; ++green)
      for (std::int32_t blue = 0; blue < 256; ++blue) {
        const YCoCgR ycocg = rgb_to_ycocg_r(red, green, blue);
        const Rgb<std::int32_t> back = ycocg_r_to_rgb(ycocg);
        if (back.r != red || back.g != green || back.b != blue) {
          FAIL() << "(" << red << ", " << green << ", " << blue << ") came back as (" << back.r << ", " << back.g
                 << ", " << back.b << ")";
        }
        // 8-bit RGB -> Y in 8 bits unsigned, Co and Cg in 9 bits signed.
        if (ycocg.y < 0 || ycocg.y > 255 || ycocg.co < -255 || ycocg.co > 255 || ycocg.cg < -255 ||
            ycocg.cg > 255) {
          FAIL() << "(" << red << ", " << green << ", " << blue << ") -> Y " << ycocg.y << " Co " << ycocg.co
                 << " Cg " << ycocg.cg << " is outside 8/9/9 bits";
        }
      }
}

TEST(YCoCgRColorSpace, MapsKnownColoursToTheLiftingValues) {
  // Worked through the lifting steps by hand: Co = R - B, t = B + floor(Co/2), Cg = G - t, Y = t + floor(Cg/2).
  struct Case {
    std::int32_t r, g, b, y, co, cg;
  };
  const Case cases[] = {
      {0, 0, 0, 0, 0, 0},            // black
      {255, 255, 255, 255, 0, 0},    // white: grey has zero chroma
      {255, 0, 0, 63, 255, -127},    // t = 127, Cg = -127, Y = 127 + floor(-63.5) = 63
      {0, 255, 0, 127, 0, 255},      // t = 0, Y = floor(255/2) = 127
      {0, 0, 255, 63, -255, -127},   // Co = -255, t = 255 + floor(-127.5) = 127, Cg = -127, Y = 127 - 64 = 63
      {255, 0, 255, 127, 0, -255},   // magenta: t = 255, Cg = -255, Y = 255 - 128 = 127
      {10, 20, 30, 20, -20, 0},      // t = 20, Cg = 0
  };
  for (const Case& c : cases) {
    const YCoCgR ycocg = rgb_to_ycocg_r(c.r, c.g, c.b);
    EXPECT_EQ(ycocg.y, c.y) << c.r << "," << c.g << "," << c.b;
    EXPECT_EQ(ycocg.co, c.co) << c.r << "," << c.g << "," << c.b;
    EXPECT_EQ(ycocg.cg, c.cg) << c.r << "," << c.g << "," << c.b;
  }
}

TEST(YCoCgRColorSpace, ChannelBitsAreNForLumaAndNPlusOneForChroma) {
  EXPECT_EQ(ycocg_r_luma_bits(8), 8);
  EXPECT_EQ(ycocg_r_chroma_bits(8), 9);
  EXPECT_EQ(ycocg_r_chroma_bits(16), 17);
}

TEST(YCoCgRColorSpace, RoundTripsRandomTriplesAtTenAndSixteenBits) {
  std::mt19937_64 engine(2003);
  for (int bits : {10, 12, 16}) {
    const std::int32_t top = (1 << bits) - 1;
    std::uniform_int_distribution<std::int32_t> channel(0, top);
    for (int i = 0; i < 200000; ++i) {
      const std::int32_t red = channel(engine), green = channel(engine), blue = channel(engine);
      const YCoCgR ycocg = rgb_to_ycocg_r(red, green, blue);
      const Rgb<std::int32_t> back = ycocg_r_to_rgb(ycocg);
      ASSERT_EQ(back.r, red);
      ASSERT_EQ(back.g, green);
      ASSERT_EQ(back.b, blue);
      ASSERT_GE(ycocg.y, 0);
      ASSERT_LE(ycocg.y, top);
      ASSERT_LE(std::abs(ycocg.co), top);
      ASSERT_LE(std::abs(ycocg.cg), top);
    }
  }
}

TEST(YCoCgRColorSpace, InverseIsExactOnEveryChromaPairForAFixedLuma) {
  // The inverse is also a bijection on its own domain: re-encoding decoded values gives the same triple.
  for (std::int32_t co = -255; co <= 255; ++co)
    for (std::int32_t cg = -255; cg <= 255; ++cg) {
      const Rgb<std::int32_t> rgb = ycocg_r_to_rgb(YCoCgR{100, co, cg});
      const YCoCgR again = rgb_to_ycocg_r(rgb.r, rgb.g, rgb.b);
      ASSERT_EQ(again.y, 100);
      ASSERT_EQ(again.co, co);
      ASSERT_EQ(again.cg, cg);
    }
}

}  // namespace
}  // namespace blocklab
