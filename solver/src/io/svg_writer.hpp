// The two pictures `rbla solve --svg DIR` writes: the collapse mechanism and the solver's
// convergence. Plain SVG text with no dependencies, so anyone can open them in a browser without
// CAD. Numbers are printed in the user's units (model.units).
#pragma once

#include "analysis/analysis_result.hpp"
#include "model/model.hpp"

#include <Eigen/Core>

#include <string>

namespace rbla::io {

struct SvgOptions {
  /// Axis looked along (0 x, 1 y, 2 z). -1 = auto: the extrusion axis of a planar result,
  /// otherwise the horizontal axis (perpendicular to gravity) along which the mechanism's
  /// translations are smallest, so in-plane mechanisms of walls are seen face-on (ties: the axis
  /// along which the model is thinnest).
  int view_axis = -1;
  /// Displayed displacement = amplitude * virtual velocity. Negative = auto: the largest vertex
  /// velocity times the amplitude is 8% of the bounding-box diagonal.
  double amplitude = -1.0;
  int width_px = 1000;  ///< page width in px (at least 300)
};

/// How the mechanism picture maps model points (m) to the page (px), with the auto choices of
/// SvgOptions resolved. Orthographic: page x = origin_x + scale * right.p, page y = origin_y -
/// scale * up.p (SVG y grows downwards, so up on the page is -gravity).
struct SvgView {
  int view_axis = 1;
  double amplitude = 0.0;                            ///< the one actually used (0: undisplaced)
  model::Vec3 right = model::Vec3::UnitX();          ///< page right
  model::Vec3 up = model::Vec3::UnitZ();             ///< page up
  model::Vec3 toward = -model::Vec3::UnitY();        ///< toward the viewer: right x up
  double scale = 1.0;                                ///< px per m
  double origin_x = 0.0, origin_y = 0.0;             ///< page position of the model origin, px
  double width = 0.0, height = 0.0;                  ///< page size, px

  Eigen::Vector2d to_page(const model::Vec3& p) const {
    return {origin_x + scale * right.dot(p), origin_y - scale * up.dot(p)};
  }
};

/// The view mechanism_svg uses for these arguments.
SvgView mechanism_view(const model::Model& model, const analysis::AnalysisResult& result,
                       const SvgOptions& options = {});

/// Undisplaced blocks as thin grey outlines, then each block moved by the exact rigid motion of
/// amplitude s, p -> g + R(s theta)(p - g) + s u (Rodrigues rotation of angle s|theta| about
/// theta/|theta|; g centroid, u translation, theta rotation), front faces painted back to front;
/// cracked interfaces coloured by state; title with the verdict and the headline number.
std::string mechanism_svg(const model::Model& model, const analysis::AnalysisResult& result,
                          const SvgOptions& options = {});

/// Two panels: the non-associative iterations (alpha or base reaction, in kN since no model
/// units are at hand) and the interior-point history of the last conic solve (relative gap,
/// primal and dual residuals on a log10 axis, values clamped at 1e-16).
std::string convergence_svg(const analysis::AnalysisResult& result);

}  // namespace rbla::io
