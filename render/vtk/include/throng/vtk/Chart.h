#pragma once
// Line and point charts written to PNG with VTK's charts, for benchmark reports. Debian's VTK renders
// through X only: the caller needs a display (or a virtual one, xvfb-run).

#include <string>
#include <vector>

namespace throng::vtk {

/// One series of a chart.
struct ChartSeries {
    /// How the series is drawn.
    enum class Style { Line, DashedLine, Points, LineAndPoints };
    std::string name;          ///< legend entry
    std::vector<double> x;     ///< abscissae
    std::vector<double> y;     ///< ordinates, as many as x
    Style style = Style::Line; ///< drawing style
    unsigned char rgb[3] = {31, 119, 180};  ///< colour
};

/// A chart: title, axis labels, series.
struct Chart {
    std::string title;                 ///< above the plot
    std::string xLabel;                ///< bottom axis
    std::string yLabel;                ///< left axis
    std::vector<ChartSeries> series;   ///< drawn in order; legend in the same order
    bool logX = false;                 ///< logarithmic bottom axis
    bool logY = false;                 ///< logarithmic left axis
    /// Where the legend goes (inside the plot, on the right).
    enum class Legend { Top, Middle, Bottom } legend = Legend::Top;  ///< the legend's place
    /// Margin added on each side of both axes, as a share of the data's range (0: VTK's tight fit,
    /// which draws points on the border half outside the plot); with a legend at the top or bottom,
    /// the left axis also leaves room for it there.
    double padding = 0.0;
    int width = 1000;                  ///< pixels
    int height = 650;                  ///< pixels
};

/// Renders `chart` off screen and writes it to `path` as PNG. Throws std::runtime_error naming the
/// problem (no X display, empty or mismatched series, unwritable file).
void writeChartPng(const Chart& chart, const std::string& path);

/// Whether an X display is available for VTK rendering.
bool displayAvailable();

/// A palette of distinguishable colours: colour `i` (cycles).
void paletteColour(int i, unsigned char rgb[3]);

}  // namespace throng::vtk
