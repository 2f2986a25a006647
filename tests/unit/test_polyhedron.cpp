// Volume, centroid and closure of polyhedra against closed forms.
#include "geometry/polyhedron.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using rbla::geometry::check_closure;
using rbla::geometry::face_geometry;
using rbla::geometry::FaceList;
using rbla::geometry::mass_properties;
using rbla::geometry::Vec3;

namespace {

struct Mesh {
  std::vector<Vec3> vertices;
  FaceList faces;
};

Mesh box(const Vec3& lo, const Vec3& hi) {
  Mesh m;
  m.vertices = {{lo.x(), lo.y(), lo.z()}, {hi.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), lo.z()}, {lo.x(), hi.y(), lo.z()},
                {lo.x(), lo.y(), hi.z()}, {hi.x(), lo.y(), hi.z()}, {hi.x(), hi.y(), hi.z()}, {lo.x(), hi.y(), hi.z()}};
  m.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  return m;
}

/// Prism over a counter-clockwise outline in the x-y plane, height h: the bottom face (the whole,
/// possibly non-convex outline) is one face.
Mesh prism(const std::vector<Eigen::Vector2d>& outline, double h) {
  Mesh m;
  const int n = static_cast<int>(outline.size());
  for (const auto& p : outline) m.vertices.emplace_back(p.x(), p.y(), 0.0);
  for (const auto& p : outline) m.vertices.emplace_back(p.x(), p.y(), h);
  std::vector<int> bottom, top;
  for (int i = n - 1; i >= 0; --i) bottom.push_back(i);
  for (int i = 0; i < n; ++i) top.push_back(n + i);
  m.faces = {bottom, top};
  for (int i = 0; i < n; ++i) m.faces.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
  return m;
}

Mesh scaled(Mesh m, double s, const Vec3& shift = Vec3::Zero()) {
  for (auto& v : m.vertices) v = v * s + shift;
  return m;
}

}  // namespace

TEST(Polyhedron, UnitCubeVolumeAndCentroid) {
  const Mesh cube = box({0, 0, 0}, {1, 1, 1});
  const auto props = mass_properties(cube.vertices, cube.faces);
  EXPECT_NEAR(props.volume, 1.0, 1e-14);
  EXPECT_NEAR((props.centroid - Vec3(0.5, 0.5, 0.5)).norm(), 0.0, 1e-14);
  EXPECT_NEAR(props.surface_area, 6.0, 1e-14);
}

TEST(Polyhedron, BoxInMillimetresAndMetresAgree) {
  const Mesh metres = box({0.1, 0.2, 0.3}, {0.54, 0.58, 0.8});
  const Mesh millimetres = scaled(metres, 1000.0);
  const auto m = mass_properties(metres.vertices, metres.faces);
  const auto mm = mass_properties(millimetres.vertices, millimetres.faces);
  EXPECT_NEAR(m.volume, 0.44 * 0.38 * 0.5, 1e-15);
  EXPECT_NEAR(mm.volume / 1e9, m.volume, 1e-12 * m.volume);
  EXPECT_NEAR((mm.centroid / 1000.0 - m.centroid).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.centroid - Vec3(0.32, 0.39, 0.55)).norm(), 0.0, 1e-14);
}

TEST(Polyhedron, TetrahedronClosedForm) {
  // V = |det| / 6 and the centroid is the vertex average.
  std::vector<Vec3> v = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {0, 0, 4}};
  FaceList faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  const auto props = mass_properties(v, faces);
  EXPECT_NEAR(props.volume, 2.0 * 3.0 * 4.0 / 6.0, 1e-14);
  EXPECT_NEAR((props.centroid - Vec3(0.5, 0.75, 1.0)).norm(), 0.0, 1e-14);
}

TEST(Polyhedron, NonConvexLPrismWithNonConvexFaces) {
  // L outline: [0,2]x[0,1] plus [0,1]x[1,3]; area 2 + 2 = 4, centroid ((2*1 + 2*0.5)/4, (2*0.5 + 2*2)/4).
  const Mesh l = prism({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}}, 0.5);
  const auto props = mass_properties(l.vertices, l.faces);
  EXPECT_NEAR(props.volume, 4.0 * 0.5, 1e-14);
  EXPECT_NEAR((props.centroid - Vec3(0.75, 1.25, 0.25)).norm(), 0.0, 1e-14);
  const auto bottom = face_geometry(l.vertices, l.faces[0]);
  EXPECT_NEAR(bottom.area, 4.0, 1e-14);
  EXPECT_NEAR((bottom.normal - Vec3(0, 0, -1)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((bottom.centroid - Vec3(0.75, 1.25, 0.0)).norm(), 0.0, 1e-14);
  EXPECT_TRUE(check_closure(l.vertices, l.faces, 1e-9).closed);
}

TEST(Polyhedron, FarFromOriginKeepsAccuracy) {
  // A 0.3 m block 1000 km from the origin: the reference point keeps round-off at the block's scale.
  const Mesh far = scaled(box({0, 0, 0}, {0.3, 0.2, 0.1}), 1.0, Vec3(1e6, -2e6, 5e5));
  const auto props = mass_properties(far.vertices, far.faces);
  EXPECT_NEAR(props.volume, 0.006, 1e-9 * 0.006 + 1e-12);
  EXPECT_NEAR((props.centroid - Vec3(1e6 + 0.15, -2e6 + 0.1, 5e5 + 0.05)).norm(), 0.0, 1e-8);
}

TEST(Polyhedron, InvertedFacesGiveNegativeVolume) {
  Mesh cube = box({0, 0, 0}, {1, 2, 3});
  for (auto& face : cube.faces) std::reverse(face.begin(), face.end());
  EXPECT_NEAR(mass_properties(cube.vertices, cube.faces).volume, -6.0, 1e-13);
  EXPECT_TRUE(check_closure(cube.vertices, cube.faces, 1e-9).closed);
}

TEST(PolyhedronClosure, OpenBoxIsNotClosed) {
  Mesh cube = box({0, 0, 0}, {1, 1, 1});
  cube.faces.pop_back();
  const auto check = check_closure(cube.vertices, cube.faces, 1e-9);
  EXPECT_FALSE(check.closed);
  EXPECT_NE(check.detail.find("no matching"), std::string::npos);
}

TEST(PolyhedronClosure, OneFlippedFaceIsInconsistent) {
  Mesh cube = box({0, 0, 0}, {1, 1, 1});
  std::reverse(cube.faces[2].begin(), cube.faces[2].end());
  const auto check = check_closure(cube.vertices, cube.faces, 1e-9);
  EXPECT_FALSE(check.consistent);
}

TEST(PolyhedronClosure, DuplicatedVerticesPerFaceAreMerged) {
  // Mesh exports often repeat vertices per face: 24 vertices for a cube.
  const Mesh cube = box({0, 0, 0}, {1, 1, 1});
  Mesh soup;
  for (const auto& face : cube.faces) {
    std::vector<int> loop;
    for (int i : face) {
      loop.push_back(static_cast<int>(soup.vertices.size()));
      soup.vertices.push_back(cube.vertices[i] + Vec3::Constant(1e-12));
    }
    soup.faces.push_back(loop);
  }
  EXPECT_TRUE(check_closure(soup.vertices, soup.faces, 1e-9).closed);
  EXPECT_NEAR(mass_properties(soup.vertices, soup.faces).volume, 1.0, 1e-12);
}

TEST(PolyhedronClosure, TJunctionIsAcceptedAfterSplitting) {
  // The top face is split in two along x = 0.5; the side faces at y = 0 and y = 1 keep a single
  // top edge, so vertices (0.5, 0, 1) and (0.5, 1, 1) lie on their edges.
  std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1},
                         {1, 1, 1}, {0, 1, 1}, {0.5, 0, 1}, {0.5, 1, 1}};
  FaceList faces = {{0, 3, 2, 1}, {4, 8, 9, 7}, {8, 5, 6, 9}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  const auto check = check_closure(v, faces, 1e-9);
  EXPECT_TRUE(check.closed);
  EXPECT_TRUE(check.needed_t_junction_split);
  EXPECT_NEAR(mass_properties(v, faces).volume, 1.0, 1e-14);
}
