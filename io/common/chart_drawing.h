// Small cairo helpers shared by the PNG map quick-looks and the time-series plots: tick
// placement, number labels, aligned text and colour ramps.
#pragma once

#include <cairo.h>
#include <string>
#include <vector>

namespace talus::chart {

/// "Nice" tick values (1, 2, 5 x 10^k steps) covering [lo, hi], about `count` of them.
std::vector<double> niceTicks(double lo, double hi, int count, double* stepOut = nullptr);
/// A nice upper bound >= v (1, 2, 2.5, 5 x 10^k), for colour-scale maxima.
double niceCeil(double v);
/// Label for a tick value, with as many decimals as the step needs.
std::string tickLabel(double value, double step);

enum class Align { Start, Centre, End };
/// Draws `text` with its anchor at (x, y); vertical Centre puts the text's middle at y.
void text(cairo_t* cr, double x, double y, const std::string& s, double size, Align h = Align::Start,
          Align v = Align::End, bool bold = false);
void textRotated(cairo_t* cr, double x, double y, const std::string& s, double size); ///< 90 deg CCW, centred

struct Rgb {
  double r, g, b;
};
enum class Ramp { Viridis, Magma, Blues, Plasma, Browns };
/// Colour of t in [0, 1] on a perceptually ordered ramp.
Rgb ramp(Ramp which, double t);

/// Distinct line colours (Tableau 10), cycling.
Rgb lineColour(int i);

/// Throws std::runtime_error when cairo failed to write the PNG.
void writePng(cairo_surface_t* surface, const std::string& path);

} // namespace talus::chart
