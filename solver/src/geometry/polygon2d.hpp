#pragma once
// 2-D polygon utilities for interface detection: two coplanar, opposite block faces are
// projected into the interface plane and their overlap is the contact polygon.
//
// Faces come from CAD exports, so exactly shared edges and vertices (stacked boxes, running
// bond) are the common case; every predicate therefore takes an absolute snapping tolerance
// `tol` in the units of the coordinates. Inside intersect() the tolerance is raised to at least
// a few ulps of the coordinate magnitude, so tol = 0 still behaves on exact input.

#include <Eigen/Core>
#include <vector>

namespace rbla::geometry {

using Point2 = Eigen::Vector2d;
using Polygon2 = std::vector<Point2>;  // simple polygon, no repeated closing vertex

/// Shoelace signed area: > 0 for counter-clockwise.
double signed_area(const Polygon2& polygon);

/// Removes consecutive duplicates (distance <= tol) and vertices whose removal moves the boundary
/// by <= tol (collinear); keeps orientation. The tolerance is checked against every vertex
/// removed so far, so long runs of nearly collinear vertices cannot drift. Zero-width spikes
/// (a vertex whose triangle with its neighbours is thinner than tol and which folds back) are
/// removed too, since they carry no area. Returns an empty polygon when fewer than 3 vertices
/// remain.
Polygon2 simplify(const Polygon2& polygon, double tol);

/// True when no two non-adjacent edges touch or cross (within tol), adjacent edges do not fold
/// back onto each other, no edge is shorter than tol, and area is non-zero.
bool is_simple(const Polygon2& polygon, double tol);

/// Point-in-polygon (non-zero winding, so either orientation); points within tol of the
/// boundary count as inside.
bool contains(const Polygon2& polygon, const Point2& p, double tol);

/// Intersection of two simple polygons (either orientation on input; non-convex allowed).
/// Returns the CCW, simplified components of the overlap region with area > min_area.
/// Regions that only touch along an edge or at a point give nothing. tol is the snapping distance
/// (absolute, same units as the coordinates): vertices/intersections closer than tol are merged.
/// Dispatches to intersect_convex() when both inputs are convex after simplification, otherwise
/// to intersect_general(). Clockwise result loops (holes, impossible for simply connected inputs
/// and only produced by snapping artefacts) are dropped.
std::vector<Polygon2> intersect(const Polygon2& a, const Polygon2& b, double tol, double min_area = 0.0);

/// Convex fast path (Sutherland-Hodgman with three-way on-line classification). Falls back to
/// intersect_general() when either input is not convex after simplification. Exposed for tests.
std::vector<Polygon2> intersect_convex(const Polygon2& a, const Polygon2& b, double tol,
                                       double min_area = 0.0);

/// General path (conforming arrangement + boundary classification), valid for any pair of simple
/// polygons. Exposed for tests and for callers that want to bypass the convexity dispatch.
std::vector<Polygon2> intersect_general(const Polygon2& a, const Polygon2& b, double tol,
                                        double min_area = 0.0);

/// True when the polygon (after removing duplicate/collinear vertices within tol) is strictly
/// convex and turns exactly once, in either orientation.
bool is_convex(const Polygon2& polygon, double tol);

}  // namespace rbla::geometry
