/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpPngPlot.h
  \brief A small headless line/scatter plot written to PNG with ViSP's drawing and font tools,
  used by the examples and tutorials (vpPlot needs a display; these programs run headless).
*/
#ifndef VP_PNG_PLOT_H
#define VP_PNG_PLOT_H

#include <string>
#include <vector>

#include <visp3/core/vpColor.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>

/*!
  \brief Headless 2D plot: axes with ticks, curves or point clouds, a legend, written as PNG.
*/
class vpPngPlot
{
public:
  //! A plot with a title and axis labels, rendered at width x height pixels.
  vpPngPlot(const std::string &title, const std::string &xLabel, const std::string &yLabel, unsigned int width = 900,
            unsigned int height = 560);
  //! Adds a polyline through (x[i], y[i]); non-finite samples break the line.
  void addCurve(const std::string &name, const std::vector<double> &x, const std::vector<double> &y,
                const vpColor &color);
  //! Adds markers at (x[i], y[i]); successive point series get a circle, a square, a plus, a cross.
  void addPoints(const std::string &name, const std::vector<double> &x, const std::vector<double> &y,
                 const vpColor &color);
  //! Fixes the x range instead of fitting the data.
  void setXRange(double xmin, double xmax);
  /*!
    Fixes the y range instead of fitting the data. A marker of addPoints() beyond it is drawn as a
    triangle on the edge of the chart, pointing out, with its value, and the legend counts them: one
    series far off (an estimator without outlier rejection) then leaves the others readable.
  */
  void setYRange(double ymin, double ymax);
  //! Logarithmic y axis (decade ticks); samples <= 0 are then left out.
  void setLogY(bool logY);
  //! Renders the plot.
  void render(vpImage<vpRGBa> &I) const;
  //! Renders and writes the plot to a PNG file (throws vpException if it cannot be written).
  void write(const std::string &filename) const;

private:
  struct Series
  {
    std::string name;
    std::vector<double> x, y;
    vpColor color;
    bool markers;
  };
  //! The plotted ordinate of \e y: y, or log10(y) on a log axis (NaN for y <= 0).
  double plotY(double y) const;
  //! Tick positions (plotted ordinates) between \e y0 and \e y1.
  std::vector<double> yTicks(double y0, double y1) const;
  void dataRange(double &x0, double &x1, double &y0, double &y1) const;
  //! Size (height, width) of the legend box of the series whose names are not empty.
  vpImagePoint legendSize(const vpFont &font) const;
  /*!
    Legend box at \e corner (top-left pixel of the box); \e clipped[k] markers of series k lie beyond
    the y range.
  */
  void drawLegend(vpImage<vpRGBa> &I, const vpFont &font, const vpImagePoint &corner,
                  const std::vector<unsigned int> &clipped) const;

  std::string m_title, m_xLabel, m_yLabel;
  unsigned int m_width, m_height;
  std::vector<Series> m_series;
  bool m_fixedX, m_fixedY, m_logY;
  double m_xmin, m_xmax, m_ymin, m_ymax;
};

#endif
