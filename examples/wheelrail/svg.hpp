// Small SVG writers for the wheel-rail example and tool: a patch's pressure map with the
// contact outlines of two solvers, and line charts of the study. No dependencies.
#pragma once

#include <fastnorm/fastnorm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace fastnorm_example {

inline std::string number(double value, const char* format = "%.4g") {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// Blue → teal → yellow for 0 ≤ t ≤ 1 (three stops of the viridis map, linear between).
inline std::string ramp(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const double stops[3][3] = {{59, 82, 139}, {33, 145, 140}, {253, 231, 37}};
  const int from = t < 0.5 ? 0 : 1;
  const double f = t < 0.5 ? 2 * t : 2 * t - 1;
  int rgb[3];
  for (int c = 0; c < 3; ++c) rgb[c] = static_cast<int>(stops[from][c] + f * (stops[from + 1][c] - stops[from][c]));
  char text[16];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
  return text;
}

// Pressure map of `reference` (cells coloured by p / pmax) with the contact outline of
// `reference` (black) and, if given, of `other` (red, dashed). Axes in mm.
inline void write_patch_svg(const std::string& path, const std::string& title, const fastnorm::Grid<double>& grid,
                            const fastnorm::Solution<double>& reference, const std::string& reference_name,
                            const fastnorm::Solution<double>* other, const std::string& other_name) {
  const double cell = std::clamp(520.0 / static_cast<double>(std::max(grid.mx(), grid.my())), 2.0, 12.0);
  const double width = cell * static_cast<double>(grid.mx()), height = cell * static_cast<double>(grid.my());
  const double left = 70, top = 40, legend = 160;
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << left + width + legend << "' height='" << top + height + 60
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='" << left << "' y='22' font-size='14'>" << title << "</text>\n";
  const double pmax = std::max(reference.pressure.maxCoeff(), 1e-30);
  // Row j is drawn with s increasing upwards.
  auto px = [&](Eigen::Index i) { return left + cell * static_cast<double>(i); };
  auto py = [&](Eigen::Index j) { return top + height - cell * static_cast<double>(j + 1); };
  for (Eigen::Index j = 0; j < grid.my(); ++j) {
    for (Eigen::Index i = 0; i < grid.mx(); ++i) {
      const double p = reference.pressure(grid.index(i, j));
      if (p <= 0) continue;
      out << "<rect x='" << px(i) << "' y='" << py(j) << "' width='" << cell + 0.3 << "' height='" << cell + 0.3
          << "' fill='" << ramp(p / pmax) << "'/>\n";
    }
  }
  // Outline: the element edges between contact and no contact.
  auto outline = [&](const fastnorm::Solution<double>& solution, const char* colour, const char* dash) {
    auto inside = [&](Eigen::Index i, Eigen::Index j) {
      return i >= 0 && j >= 0 && i < grid.mx() && j < grid.my() && solution.in_contact(grid.index(i, j));
    };
    out << "<path fill='none' stroke='" << colour << "' stroke-width='1.6' stroke-dasharray='" << dash << "' d='";
    for (Eigen::Index j = 0; j < grid.my(); ++j) {
      for (Eigen::Index i = 0; i < grid.mx(); ++i) {
        if (!inside(i, j)) continue;
        const double x0 = px(i), x1 = px(i) + cell, y0 = py(j) + cell, y1 = py(j);
        if (!inside(i - 1, j)) out << "M" << x0 << ' ' << y0 << "V" << y1;
        if (!inside(i + 1, j)) out << "M" << x1 << ' ' << y0 << "V" << y1;
        if (!inside(i, j - 1)) out << "M" << x0 << ' ' << y0 << "H" << x1;
        if (!inside(i, j + 1)) out << "M" << x0 << ' ' << y1 << "H" << x1;
      }
    }
    out << "'/>\n";
  };
  outline(reference, "black", "none");
  if (other) outline(*other, "#d62728", "4 3");
  // Frame, axis labels (mm) at the ends.
  out << "<rect x='" << left << "' y='" << top << "' width='" << width << "' height='" << height
      << "' fill='none' stroke='#888'/>\n";
  const double x_first = grid.x(0) - grid.dx() / 2, x_last = grid.x(grid.mx() - 1) + grid.dx() / 2;
  const double y_first = grid.y(0) - grid.dy() / 2, y_last = grid.y(grid.my() - 1) + grid.dy() / 2;
  out << "<text x='" << left << "' y='" << top + height + 16 << "'>" << number(x_first * 1e3, "%.2f") << "</text>\n"
      << "<text x='" << left + width << "' y='" << top + height + 16 << "' text-anchor='end'>" << number(x_last * 1e3, "%.2f")
      << "</text>\n<text x='" << left + width / 2 << "' y='" << top + height + 34
      << "' text-anchor='middle'>x, rolling direction (mm)</text>\n"
      << "<text x='" << left - 6 << "' y='" << top + height << "' text-anchor='end'>" << number(y_first * 1e3, "%.2f")
      << "</text>\n<text x='" << left - 6 << "' y='" << top + 10 << "' text-anchor='end'>" << number(y_last * 1e3, "%.2f")
      << "</text>\n<text x='18' y='" << top + height / 2 << "' transform='rotate(-90 18 " << top + height / 2
      << ")' text-anchor='middle'>s, lateral (mm)</text>\n";
  // Legend.
  const double lx = left + width + 20;
  for (int k = 0; k <= 10; ++k) {
    out << "<rect x='" << lx << "' y='" << top + 150 - 15 * k << "' width='14' height='15' fill='" << ramp(k / 10.0) << "'/>\n";
  }
  out << "<text x='" << lx + 20 << "' y='" << top + 12 << "'>" << number(pmax / 1e6, "%.0f") << " MPa</text>\n"
      << "<text x='" << lx + 20 << "' y='" << top + 162 << "'>0</text>\n"
      << "<path d='M" << lx << ' ' << top + 190 << "h24' stroke='black' stroke-width='1.6'/><text x='" << lx + 30 << "' y='"
      << top + 194 << "'>" << reference_name << "</text>\n";
  if (other) {
    out << "<path d='M" << lx << ' ' << top + 210 << "h24' stroke='#d62728' stroke-width='1.6' stroke-dasharray='4 3'/>"
        << "<text x='" << lx + 30 << "' y='" << top + 214 << "'>" << other_name << "</text>\n";
  }
  out << "</svg>\n";
}

// One curve of a line chart.
struct Series {
  std::string name;
  std::vector<double> x, y;
};

// A line chart; `log_y` plots log10 of y (non-positive values skipped).
inline void write_line_chart(const std::string& path, const std::string& title, const std::string& x_label,
                             const std::string& y_label, const std::vector<Series>& series, bool log_y) {
  const double left = 80, top = 40, width = 560, height = 360, legend = 190;
  auto value = [&](double y) { return log_y ? std::log10(y) : y; };
  double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
  for (const auto& s : series) {
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (log_y && !(s.y[k] > 0)) continue;
      x_min = std::min(x_min, s.x[k]), x_max = std::max(x_max, s.x[k]);
      y_min = std::min(y_min, value(s.y[k])), y_max = std::max(y_max, value(s.y[k]));
    }
  }
  if (x_min > x_max) x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  if (x_max == x_min) x_max = x_min + 1;
  if (log_y) y_min = std::floor(y_min), y_max = std::ceil(y_max);
  if (y_max == y_min) y_max = y_min + 1;
  auto px = [&](double x) { return left + (x - x_min) / (x_max - x_min) * width; };
  auto py = [&](double y) { return top + height - (value(y) - y_min) / (y_max - y_min) * height; };
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << left + width + legend << "' height='" << top + height + 60
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='" << left << "' y='22' font-size='14'>" << title << "</text>\n"
      << "<rect x='" << left << "' y='" << top << "' width='" << width << "' height='" << height
      << "' fill='none' stroke='#888'/>\n";
  for (int k = 0; k <= 6; ++k) {  // x ticks
    const double x = x_min + (x_max - x_min) * k / 6;
    out << "<text x='" << px(x) << "' y='" << top + height + 16 << "' text-anchor='middle'>" << number(x, "%.3g") << "</text>\n";
  }
  const int y_ticks = log_y ? static_cast<int>(y_max - y_min) : 5;
  for (int k = 0; k <= y_ticks; ++k) {
    const double level = y_min + (y_max - y_min) * k / y_ticks;
    const double y = top + height - (level - y_min) / (y_max - y_min) * height;
    out << "<path d='M" << left << ' ' << y << "h" << width << "' stroke='#eee'/>\n<text x='" << left - 6 << "' y='"
        << y + 4 << "' text-anchor='end'>" << (log_y ? "1e" + number(level, "%.0f") : number(level, "%.3g")) << "</text>\n";
  }
  out << "<text x='" << left + width / 2 << "' y='" << top + height + 36 << "' text-anchor='middle'>" << x_label
      << "</text>\n<text x='18' y='" << top + height / 2 << "' transform='rotate(-90 18 " << top + height / 2
      << ")' text-anchor='middle'>" << y_label << "</text>\n";
  const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
                           "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000"};
  for (std::size_t n = 0; n < series.size(); ++n) {
    const auto& s = series[n];
    const char* colour = colours[n % 11];
    out << "<path fill='none' stroke='" << colour << "' stroke-width='1.5' d='";
    bool pen_down = false;
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (log_y && !(s.y[k] > 0)) {
        pen_down = false;
        continue;
      }
      out << (pen_down ? "L" : "M") << px(s.x[k]) << ' ' << py(s.y[k]);
      pen_down = true;
    }
    out << "'/>\n";
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (log_y && !(s.y[k] > 0)) continue;
      out << "<circle cx='" << px(s.x[k]) << "' cy='" << py(s.y[k]) << "' r='2.5' fill='" << colour << "'/>\n";
    }
    out << "<path d='M" << left + width + 15 << ' ' << top + 10 + 18 * static_cast<double>(n) << "h20' stroke='" << colour
        << "' stroke-width='2'/><text x='" << left + width + 40 << "' y='" << top + 14 + 18 * static_cast<double>(n)
        << "'>" << s.name << "</text>\n";
  }
  out << "</svg>\n";
}

}  // namespace fastnorm_example
