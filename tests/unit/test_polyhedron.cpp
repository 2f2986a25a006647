// Volume, centroid and closure of polyhedra against closed forms.
#include "geometry/polyhedron.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

using rbla::geometry::check_closure;
using rbla::geometry::face_geometry;
using rbla::geometry::FaceList;
using rbla::geometry::mass_properties;
using rbla::geometry::merge_close_vertices;
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

// A face's list may start at any corner. With warped faces, a fan from the first corner gave
// another surface for each start: rolling the lists of a generated vault's block moved its
// centroid by 12.5 mm and its volume by 1.3 %. The fan from the corners' mean does not depend on it.
TEST(Polyhedron, WarpedFacesGiveTheSameMassWhicheverCornerTheirListsStartAt) {
  Mesh warped = box(Vec3(0, 0, 0), Vec3(1, 0.5, 0.3));
  warped.vertices[6] += Vec3(0.05, -0.03, 0.08);  // one top corner out of its three faces' planes
  const auto reference = mass_properties(warped.vertices, warped.faces);
  for (std::size_t roll = 1; roll < 4; ++roll) {
    Mesh rolled = warped;
    for (auto& face : rolled.faces) std::rotate(face.begin(), face.begin() + static_cast<std::ptrdiff_t>(roll % face.size()), face.end());
    const auto m = mass_properties(rolled.vertices, rolled.faces);
    EXPECT_NEAR(m.volume, reference.volume, 1e-14) << roll;
    EXPECT_NEAR((m.centroid - reference.centroid).norm(), 0.0, 1e-14) << roll;
    for (std::size_t f = 0; f < rolled.faces.size(); ++f) {
      const auto a = rbla::geometry::face_geometry(warped.vertices, warped.faces[f]);
      const auto b = rbla::geometry::face_geometry(rolled.vertices, rolled.faces[f]);
      EXPECT_NEAR((a.centroid - b.centroid).norm(), 0.0, 1e-14) << roll << " face " << f;
    }
  }
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

namespace {

/// Single linkage by testing every pair: the reference the grid-based merge must agree with.
std::vector<int> merge_by_every_pair(const std::vector<Vec3>& v, double tol) {
  std::vector<int> parent(v.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a];
    return a;
  };
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (std::size_t j = i + 1; j < v.size(); ++j) {
      if ((v[i] - v[j]).norm() <= tol) {
        const int a = find(static_cast<int>(i)), b = find(static_cast<int>(j));
        parent[std::max(a, b)] = std::min(a, b);
      }
    }
  }
  std::vector<int> root(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) root[i] = find(static_cast<int>(i));
  return root;
}

/// A box whose faces x = 0 and x = 1 are n x n grids of quads, the four other faces single quads:
/// 2 (n + 1)^2 vertices, all of each grid sharing one x, and T-junctions along the grids' borders.
Mesh box_with_meshed_x_faces(int n) {
  Mesh m;
  auto id = [&](int side, int j, int k) { return side * (n + 1) * (n + 1) + j * (n + 1) + k; };
  for (int side = 0; side < 2; ++side) {
    for (int j = 0; j <= n; ++j) {
      for (int k = 0; k <= n; ++k) m.vertices.emplace_back(side, double(j) / n, double(k) / n);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < n; ++k) {
      m.faces.push_back({id(0, j, k), id(0, j, k + 1), id(0, j + 1, k + 1), id(0, j + 1, k)});  // outward -x
      m.faces.push_back({id(1, j, k), id(1, j + 1, k), id(1, j + 1, k + 1), id(1, j, k + 1)});  // outward +x
    }
  }
  m.faces.push_back({id(0, 0, 0), id(0, n, 0), id(1, n, 0), id(1, 0, 0)});  // z = 0, outward -z
  m.faces.push_back({id(0, 0, n), id(1, 0, n), id(1, n, n), id(0, n, n)});  // z = 1
  m.faces.push_back({id(0, 0, 0), id(1, 0, 0), id(1, 0, n), id(0, 0, n)});  // y = 0
  m.faces.push_back({id(0, n, 0), id(0, n, n), id(1, n, n), id(1, n, 0)});  // y = 1
  return m;
}

}  // namespace

TEST(VertexMerging, AgreesWithEveryPairSingleLinkage) {
  // Clusters of jittered copies, chains just under the tolerance, and isolated points, at
  // tolerances from far below to above the jitter; the reference tests every pair.
  std::mt19937 random(19);
  std::uniform_real_distribution<double> unit(0.0, 1.0), jitter(-1e-3, 1e-3);
  std::vector<Vec3> v;
  for (int c = 0; c < 300; ++c) {
    const Vec3 centre(unit(random), unit(random), unit(random));
    const int copies = 1 + c % 5;
    for (int k = 0; k < copies; ++k) v.push_back(centre + Vec3(jitter(random), jitter(random), jitter(random)));
  }
  for (int k = 0; k < 50; ++k) v.emplace_back(0.5 + k * 0.99e-3, 0.25, 0.75);  // a chain along x
  for (const double tol : {0.0, 1e-6, 5e-4, 1e-3, 2e-3, 1e-2}) {
    EXPECT_EQ(merge_close_vertices(v, tol), merge_by_every_pair(v, tol)) << "tol " << tol;
  }
}

TEST(VertexMerging, ManyCopiesOfOnePointAreOneVertex) {
  std::vector<Vec3> v(200000, Vec3(1, 2, 3));
  v.emplace_back(2, 2, 3);
  const auto merged = merge_close_vertices(v, 1e-6);
  EXPECT_TRUE(std::all_of(merged.begin(), merged.end() - 1, [](int c) { return c == 0; }));
  EXPECT_EQ(merged.back(), static_cast<int>(v.size()) - 1);
}

TEST(PolyhedronClosure, FinelyMeshedFacesSharingACoordinateCloseInNearLinearTime) {
  // 2 x 201^2 = 80802 vertices, half of them at x = 0 and half at x = 1: the sweep along x that
  // merged vertices compared every pair within each half (3.3e9 tests), and the T-junction pass
  // tested every edge against every vertex (2.6e10). Correctness is asserted here; the cost is
  // what changed (O(n log n) now).
  const Mesh m = box_with_meshed_x_faces(200);
  const auto check = check_closure(m.vertices, m.faces, 1e-9);
  EXPECT_TRUE(check.closed) << check.detail;
  EXPECT_TRUE(check.consistent) << check.detail;
  EXPECT_TRUE(check.needed_t_junction_split);
  EXPECT_NEAR(mass_properties(m.vertices, m.faces).volume, 1.0, 1e-12);
}

TEST(PolyhedronClosure, AMissingGridQuadIsStillOpen) {
  Mesh m = box_with_meshed_x_faces(20);
  m.faces.erase(m.faces.begin() + 37);
  const auto check = check_closure(m.vertices, m.faces, 1e-9);
  EXPECT_FALSE(check.closed);
}
