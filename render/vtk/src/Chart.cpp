#include "throng/vtk/Chart.h"
#include "throng/vtk/WindowPng.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <filesystem>
#include <stdexcept>

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

namespace throng::vtk {

bool displayAvailable() {
    const char* d = std::getenv("DISPLAY");
    return d && *d;
}

void paletteColour(int i, unsigned char rgb[3]) {
    static const unsigned char colours[][3] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44},  {214, 39, 40},
                                               {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {127, 127, 127},
                                               {188, 189, 34},  {23, 190, 207}};
    const auto& c = colours[static_cast<std::size_t>(i) % (sizeof colours / sizeof colours[0])];
    rgb[0] = c[0], rgb[1] = c[1], rgb[2] = c[2];
}

void writeChartPng(const Chart& chart, const std::string& path) {
    if (!displayAvailable())
        throw std::runtime_error("writeChartPng: no X display for VTK (DISPLAY is not set); run under xvfb-run -a");
    if (chart.series.empty()) throw std::runtime_error("writeChartPng: chart '" + chart.title + "' has no series");
    for (const ChartSeries& s : chart.series)
        if (s.x.size() != s.y.size() || s.x.empty())
            throw std::runtime_error("writeChartPng: series '" + s.name + "' of chart '" + chart.title +
                                     "' has " + std::to_string(s.x.size()) + " x and " + std::to_string(s.y.size()) + " y values");

    vtkNew<vtkContextView> view;
    view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
    view->GetRenderWindow()->SetSize(chart.width, chart.height);
    view->GetRenderWindow()->SetOffScreenRendering(1);
    vtkNew<vtkChartXY> xy;
    view->GetScene()->AddItem(xy);
    xy->SetTitle(chart.title);
    xy->GetTitleProperties()->SetFontSize(20);
    xy->SetShowLegend(true);
    xy->GetLegend()->GetLabelProperties()->SetFontSize(14);
    xy->GetLegend()->SetVerticalAlignment(chart.legend == Chart::Legend::Top      ? vtkChartLegend::TOP
                                          : chart.legend == Chart::Legend::Middle ? vtkChartLegend::CENTER
                                                                                  : vtkChartLegend::BOTTOM);
    vtkAxis* bottom = xy->GetAxis(vtkAxis::BOTTOM);
    vtkAxis* left = xy->GetAxis(vtkAxis::LEFT);
    bottom->SetTitle(chart.xLabel);
    left->SetTitle(chart.yLabel);
    bottom->GetTitleProperties()->SetFontSize(16);
    left->GetTitleProperties()->SetFontSize(16);
    bottom->GetLabelProperties()->SetFontSize(13);
    left->GetLabelProperties()->SetFontSize(13);
    bottom->SetLogScale(chart.logX);
    left->SetLogScale(chart.logY);

    std::vector<vtkSmartPointer<vtkTable>> tables;  // the chart keeps references to its inputs
    for (const ChartSeries& s : chart.series) {
        auto table = vtkSmartPointer<vtkTable>::New();
        vtkNew<vtkDoubleArray> xs, ys;
        xs->SetName("x");
        ys->SetName(s.name.c_str());
        for (std::size_t i = 0; i < s.x.size(); ++i) {
            xs->InsertNextValue(s.x[i]);
            ys->InsertNextValue(s.y[i]);
        }
        table->AddColumn(xs);
        table->AddColumn(ys);
        const int type = s.style == ChartSeries::Style::Points ? vtkChart::POINTS : vtkChart::LINE;
        vtkPlot* plot = xy->AddPlot(type);
        plot->SetInputData(table, 0, 1);
        plot->SetColor(s.rgb[0], s.rgb[1], s.rgb[2], 255);
        plot->SetWidth(s.style == ChartSeries::Style::Points ? 6.0f : 2.5f);
        if (s.style == ChartSeries::Style::DashedLine) plot->GetPen()->SetLineType(vtkPen::DASH_LINE);
        if (auto* points = vtkPlotPoints::SafeDownCast(plot); points && s.style != ChartSeries::Style::Points) {
            points->SetMarkerStyle(s.style == ChartSeries::Style::LineAndPoints ? vtkPlotPoints::CIRCLE : vtkPlotPoints::NONE);
            points->SetMarkerSize(9.0f);
        }
        plot->SetLabel(s.name);
        tables.push_back(table);
    }
    if (chart.padding > 0) {
        // The data's range on each axis, widened (in log space on a log axis).
        const auto pad = [&](vtkAxis* axis, bool log, bool isX) {
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (const ChartSeries& s : chart.series)
                for (double v : isX ? s.x : s.y)
                    if (std::isfinite(v) && (!log || v > 0)) lo = std::min(lo, v), hi = std::max(hi, v);
            if (!(lo <= hi)) return;
            if (log) lo = std::log10(lo), hi = std::log10(hi);
            const double margin = hi > lo ? chart.padding * (hi - lo) : std::max(std::abs(lo), 1.0) * 0.1;
            lo -= margin, hi += margin;
            if (!isX && chart.legend != Chart::Legend::Middle) {
                // Room for the legend above or below the data, so that it hides no point.
                const double share = std::min(0.6, (20.0 * double(chart.series.size()) + 16.0) / std::max(100.0, chart.height - 120.0));
                const double room = (hi - lo) * share / (1.0 - share);
                (chart.legend == Chart::Legend::Top ? hi : lo) += chart.legend == Chart::Legend::Top ? room : -room;
            }
            if (log) lo = std::pow(10.0, lo), hi = std::pow(10.0, hi);
            axis->SetBehavior(vtkAxis::FIXED);
            axis->SetRange(lo, hi);
        };
        pad(bottom, chart.logX, true);
        pad(left, chart.logY, false);
    }
    view->GetRenderWindow()->Render();
    try {
        writeWindowPng(*view->GetRenderWindow(), path);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string("writeChartPng: ") + e.what());
    }
}

}  // namespace throng::vtk
