// The benchmarks' shared command line (benchmarks/bench_args.h), on CLI11.
#include "benchmarks/bench_args.h"

#include <iostream>
#include <memory>

namespace blocklab {
namespace bench {
namespace {

// CLI11's help with the benchmark's own usage line in place of the generic "Usage: NAME [OPTIONS]".
class UsageFormatter : public CLI::Formatter {
 public:
  explicit UsageFormatter(std::string usage) : usage_(std::move(usage)) {}
  std::string make_usage(const CLI::App*, std::string name) const override {
    return "usage: " + name + " " + usage_ + "\n";
  }

 private:
  std::string usage_;
};

}  // namespace

CommandLine::CommandLine(const std::string& name, const std::string& usage, const std::string& description)
    : app_(description, name) {
  app_.formatter(std::make_shared<UsageFormatter>(usage));
  app_.get_formatter()->column_width(24);
}

CLI::Option* CommandLine::add_data(std::string& root, const std::string& help) {
  return app_.add_option("--data", root, help)->type_name("DIR")->capture_default_str();
}

CLI::Option* CommandLine::add_list(const std::string& flag, std::vector<std::string>& values, const std::string& help) {
  return app_.add_option(flag, values, help)->delimiter(',')->type_name("a,b,...")->capture_default_str();
}

CLI::Option* CommandLine::add_integer(const std::string& name, int& value, int lo, int hi, const std::string& help) {
  return app_.add_option(name, value, help)->type_name("N")->check(CLI::Range(lo, hi))->capture_default_str();
}

CLI::Option* CommandLine::add_repeat(int& rounds, const std::string& help) {
  return add_integer("--repeat", rounds, 1, 1000, help);
}

CLI::Option* CommandLine::add_csv(std::string& path, const std::string& help) {
  return app_.add_option("--csv", path, help)->type_name("FILE");
}

CLI::Option* CommandLine::add_settings(FormatOptions& options, const std::string& help) {
  const CLI::Validator key_value(
      [](std::string& setting) {
        return setting.find('=') == std::string::npos ? "needs key=value, got '" + setting + "'" : std::string();
      },
      "");
  return app_
      .add_option_function<std::vector<std::string>>(
          "--set",
          [&options](const std::vector<std::string>& settings) {
            for (const std::string& setting : settings) {
              const std::size_t eq = setting.find('=');
              options[setting.substr(0, eq)] = setting.substr(eq + 1);
            }
          },
          help)
      ->type_name("key=value")
      ->check(key_value);
}

CLI::Option* CommandLine::add_no_astcenc(bool& astcenc) {
  return app_.add_flag_callback("--no-astcenc", [&astcenc] { astcenc = false; }, "no astcenc rows");
}

std::optional<int> CommandLine::parse(int argc, char** argv) {
  try {
    app_.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app_.help();
    return 0;
  } catch (const CLI::ParseError& error) {
    std::cerr << app_.get_name() << ": " << error.what() << " (--help lists the options)\n";
    return 2;
  }
  return std::nullopt;
}

}  // namespace bench
}  // namespace blocklab
