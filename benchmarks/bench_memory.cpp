// Peak memory of encoding (and decoding) a 4096x4096 RGBA float image with each registered format, in a fresh
// child process per format so each peak is its own. Goal (foundation issue): peak resident set < 1 GiB.
// Usage: bench_memory [size=4096] [threads=0]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "benchmarks/bench_args.h"
#include "formats/registry.h"

namespace {

// A deterministic HDR test pattern: smooth gradients over 16 stops plus hashed noise, alpha ramp.
blocklab::Image make_image(int size) {
  blocklab::Image image(size, size, 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      float* t = image.texel(x, y);
      const unsigned h = (static_cast<unsigned>(x) * 73856093u) ^ (static_cast<unsigned>(y) * 19349663u);
      const float noise = static_cast<float>(h % 1000u) / 1000.0f;
      const float stops = 16.0f * static_cast<float>(x) / static_cast<float>(size) - 8.0f;
      t[0] = std::exp2(stops) * (0.5f + 0.5f * noise);
      t[1] = std::exp2(stops) * (0.25f + 0.75f * static_cast<float>(y) / static_cast<float>(size));
      t[2] = std::exp2(-stops) * 0.01f;
      t[3] = static_cast<float>(y) / static_cast<float>(size);
    }
  return image;
}

double peak_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;   // ru_maxrss is in KiB on Linux
}

}  // namespace

int main(int argc, char** argv) {
  int size = 4096, threads = 0;
  blocklab::bench::CommandLine command_line(
      "bench_memory", "[size=4096] [threads=0]",
      "Peak memory of encoding and decoding a size x size RGBA float image with each registered format, each in a "
      "child process of its own (goal: < 1 GiB).");
  command_line.add_integer("size", size, 1, 65536, "image side");
  command_line.add_integer("threads", threads, 0, 1024, "worker threads (0: all hardware threads)");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  constexpr double kBudgetMiB = 1024.0;
  std::printf("format      image        encode_s  decode_s  peak_MiB  peak/budget(1 GiB)\n");
  std::fflush(stdout);   // else each forked child would print the buffered header again
  for (const blocklab::Format* format : blocklab::all_formats()) {
    const pid_t child = fork();
    if (child == 0) {
      const blocklab::Image image = make_image(size);
      const auto options = blocklab::resolve_format_options(*format, {});
      blocklab::CodecContext context;
      context.threads = threads;
      const auto t0 = std::chrono::steady_clock::now();
      const blocklab::EncodedTexture texture = format->encode(image, options, context);
      const auto t1 = std::chrono::steady_clock::now();
      const blocklab::Image decoded = format->decode(texture, context);
      const auto t2 = std::chrono::steady_clock::now();
      const double peak = peak_mib();
      std::printf("%-10s  %5dx%-5d  %8.3f  %8.3f  %8.1f  %6.3f\n", format->name().c_str(), size, size,
                  std::chrono::duration<double>(t1 - t0).count(), std::chrono::duration<double>(t2 - t1).count(),
                  peak, peak / kBudgetMiB);
      std::fflush(stdout);
      std::_Exit(decoded.width == size ? 0 : 1);
    }
    int status = 0;
    waitpid(child, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::fprintf(stderr, "bench_memory: %s failed\n", format->name().c_str());
      return 1;
    }
  }
  return 0;
}
