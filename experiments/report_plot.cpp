// The report's plot (experiments/report.h): error against encode time at one bit rate, written as SVG directly.
// Choice: SVG from C++ rather than matplotlib through /usr/bin/python3, so `blocklab report` needs no Python
// runtime, the figure is inline in the page (one self-contained file with its PNGs), text stays selectable, and
// the bytes do not depend on a plotting library's version. x: encode seconds on a log10 axis; y: the metric
// (linear), with an arrow saying which direction is better; each point has its name beside it and as a <title>.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "experiments/report.h"

namespace blocklab {

namespace {

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

// Round tick values: 1, 2, 5 x 10^k covering [low, high], at most about `count` of them.
std::vector<double> linear_ticks(double low, double high, int count) {
  const double span = high - low;
  const double raw = span / count;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double factor : {1.0, 2.0, 5.0, 10.0})
    if (raw <= factor * magnitude) {
      step = factor * magnitude;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(low / step) * step; t <= high + 1e-12 * span; t += step) ticks.push_back(t);
  return ticks;
}

}  // namespace

std::string error_time_svg(const std::string& title, const std::string& metric, bool higher_is_better,
                           const std::vector<PlotPoint>& points) {
  constexpr double kWidth = 640, kHeight = 400, kLeft = 70, kRight = 190, kTop = 40, kBottom = 50;
  std::vector<PlotPoint> shown;
  for (const PlotPoint& p : points)
    if (std::isfinite(p.value) && std::isfinite(p.seconds) && p.seconds > 0) shown.push_back(p);
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + number(kWidth) + "\" height=\"" +
                    number(kHeight) + "\" viewBox=\"0 0 " + number(kWidth) + " " + number(kHeight) +
                    "\" font-family=\"sans-serif\" font-size=\"11\" role=\"img\" class=\"plot\">\n"
                    "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
                    "<text x=\"" + number(kWidth / 2) + "\" y=\"20\" text-anchor=\"middle\" font-size=\"13\">" +
                    escape_markup(title) + "</text>\n";
  if (shown.empty()) {
    svg += "<text x=\"" + number(kWidth / 2) + "\" y=\"" + number(kHeight / 2) +
           "\" text-anchor=\"middle\">no finite point to plot</text>\n</svg>\n";
    return svg;
  }
  double x_low = 1e300, x_high = -1e300, y_low = 1e300, y_high = -1e300;
  for (const PlotPoint& p : shown) {
    x_low = std::min(x_low, std::log10(p.seconds));
    x_high = std::max(x_high, std::log10(p.seconds));
    y_low = std::min(y_low, p.value);
    y_high = std::max(y_high, p.value);
  }
  x_low = std::floor(x_low - 0.05);
  x_high = std::ceil(x_high + 0.05);
  const double y_pad = y_high > y_low ? 0.08 * (y_high - y_low) : std::max(0.05 * std::fabs(y_high), 0.01);
  y_low -= y_pad;
  y_high += y_pad;
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  const auto px = [&](double seconds) { return kLeft + (std::log10(seconds) - x_low) / (x_high - x_low) * plot_w; };
  const auto py = [&](double value) { return kTop + (y_high - value) / (y_high - y_low) * plot_h; };
  svg += "<rect x=\"" + number(kLeft) + "\" y=\"" + number(kTop) + "\" width=\"" + number(plot_w) + "\" height=\"" +
         number(plot_h) + "\" fill=\"none\" stroke=\"#444\"/>\n";
  for (double decade = x_low; decade <= x_high + 1e-9; decade += 1.0) {
    const double x = kLeft + (decade - x_low) / (x_high - x_low) * plot_w;
    svg += "<line x1=\"" + number(x) + "\" y1=\"" + number(kTop) + "\" x2=\"" + number(x) + "\" y2=\"" +
           number(kTop + plot_h) + "\" stroke=\"#ddd\"/>\n<text x=\"" + number(x) + "\" y=\"" +
           number(kTop + plot_h + 15) + "\" text-anchor=\"middle\">" + number(std::pow(10.0, decade)) + "</text>\n";
  }
  for (double tick : linear_ticks(y_low, y_high, 6)) {
    const double y = py(tick);
    svg += "<line x1=\"" + number(kLeft) + "\" y1=\"" + number(y) + "\" x2=\"" + number(kLeft + plot_w) + "\" y2=\"" +
           number(y) + "\" stroke=\"#eee\"/>\n<text x=\"" + number(kLeft - 5) + "\" y=\"" + number(y + 4) +
           "\" text-anchor=\"end\">" + number(tick) + "</text>\n";
  }
  svg += "<text x=\"" + number(kLeft + plot_w / 2) + "\" y=\"" + number(kHeight - 12) +
         "\" text-anchor=\"middle\">encode seconds (log scale)</text>\n<text transform=\"translate(16 " +
         number(kTop + plot_h / 2) + ") rotate(-90)\" text-anchor=\"middle\">" + escape_markup(metric) + " (" +
         (higher_is_better ? "higher" : "lower") + " is better)</text>\n";
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  for (std::size_t i = 0; i < shown.size(); ++i) {
    const PlotPoint& p = shown[i];
    const char* colour = kColours[i % 10];
    const double x = px(p.seconds), y = py(p.value);
    svg += "<circle cx=\"" + number(x) + "\" cy=\"" + number(y) + "\" r=\"4\" fill=\"" + colour + "\"><title>" +
           escape_markup(p.name) + ": " + number(p.value) + " at " + number(p.seconds) + " s</title></circle>\n";
    const double legend_y = kTop + 6 + 14.0 * static_cast<double>(i);
    if (legend_y < kHeight - 10)
      svg += "<circle cx=\"" + number(kLeft + plot_w + 12) + "\" cy=\"" + number(legend_y - 4) + "\" r=\"4\" fill=\"" +
             colour + "\"/><text x=\"" + number(kLeft + plot_w + 20) + "\" y=\"" + number(legend_y) + "\">" +
             escape_markup(p.name.size() > 28 ? p.name.substr(0, 27) + "…" : p.name) + "</text>\n";
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace blocklab
