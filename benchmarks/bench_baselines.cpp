// Throughput of the baseline formats and of the metrics on a real HDR image (Google Benchmark).
// Usage: bench_baselines [--image PATH] [google-benchmark flags]; default image: samples/hdr/Desk.exr.
// Reports megapixels per second (items = pixels) at 1 thread and at all threads.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "benchmarks/bench_args.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace {

std::string g_image_path = std::string(BLOCKLAB_SOURCE_DIR) + "/samples/hdr/Desk.exr";

const blocklab::Image& test_image() {
  static const blocklab::Image image = [] {
    blocklab::Image img = blocklab::read_image(g_image_path);
    blocklab::apply_input_policy(img, blocklab::InputPolicy::clamp, g_image_path);
    return img;
  }();
  return image;
}

void BM_Encode(benchmark::State& state, const std::string& format_name) {
  const blocklab::Format& format = blocklab::find_format(format_name);
  const auto options = blocklab::resolve_format_options(format, {});
  blocklab::CodecContext context;
  context.threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(format.encode(test_image(), options, context));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * test_image().texel_count()));
}

void BM_Decode(benchmark::State& state, const std::string& format_name) {
  const blocklab::Format& format = blocklab::find_format(format_name);
  const auto options = blocklab::resolve_format_options(format, {});
  blocklab::CodecContext context;
  context.threads = static_cast<int>(state.range(0));
  const auto texture = format.encode(test_image(), options, context);
  for (auto _ : state) benchmark::DoNotOptimize(format.decode(texture, context));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * test_image().texel_count()));
}

void BM_Metric(benchmark::State& state, const std::string& metric_name) {
  const blocklab::Metric& metric = blocklab::find_metric(metric_name);
  const blocklab::Format& format = blocklab::find_format("rgbe");
  const auto texture = format.encode(test_image(), blocklab::resolve_format_options(format, {}), {});
  const blocklab::Image decoded = format.decode(texture, {});
  for (auto _ : state) benchmark::DoNotOptimize(metric.compute(test_image(), decoded, {}));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * test_image().texel_count()));
}

}  // namespace

int main(int argc, char** argv) {
  blocklab::bench::CommandLine command_line(
      "bench_baselines", "[--image PATH] [google-benchmark flags]",
      "Throughput of the baseline formats and of the metrics on a real HDR image (Google Benchmark).");
  command_line.app().add_option("--image", g_image_path, "HDR image")->type_name("PATH")->capture_default_str();
  command_line.app().allow_extras();
  command_line.app().footer("Other flags go to Google Benchmark (e.g. --benchmark_filter=REGEX, "
                            "--benchmark_repetitions=N, --benchmark_format=json).");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  std::vector<std::string> benchmark_args = command_line.app().remaining();
  std::vector<char*> benchmark_argv = {argv[0]};
  for (std::string& arg : benchmark_args) benchmark_argv.push_back(arg.data());
  int benchmark_argc = static_cast<int>(benchmark_argv.size());
  for (const std::string name : {"fp16", "rgbe"}) {
    benchmark::RegisterBenchmark(("encode/" + name).c_str(), BM_Encode, name)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("decode/" + name).c_str(), BM_Decode, name)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
  }
  for (const std::string name : {"log2rgb", "mpsnr", "mpsnr_auto", "pu21_psnr"})
    benchmark::RegisterBenchmark(("metric/" + name).c_str(), BM_Metric, name)->Unit(benchmark::kMillisecond);
  benchmark::Initialize(&benchmark_argc, benchmark_argv.data());
  if (benchmark::ReportUnrecognizedArguments(benchmark_argc, benchmark_argv.data())) return 2;
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
