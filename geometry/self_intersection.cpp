#include "geometry/self_intersection.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

#include "geometry/cgal_surface_internal.hpp"
#include "geometry/error.hpp"

namespace vcontact::geometry {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = detail::CgalSurface;

// The mesh as a CGAL surface, face i of the mesh as face i of the surface. A vertex where two
// parts of the surface touch at one point only is split first (orient_polygon_soup), as CGAL's
// halfedge structure needs; that keeps the faces and their order.
SurfaceMesh toSurface(const TriangleMesh& mesh) {
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> faces;
  points.reserve(static_cast<std::size_t>(mesh.vertexCount()));
  for (Eigen::Index i = 0; i < mesh.vertexCount(); ++i) {
    points.emplace_back(mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2));
  }
  faces.reserve(static_cast<std::size_t>(mesh.triangleCount()));
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    faces.push_back({static_cast<std::size_t>(mesh.triangles(f, 0)),
                     static_cast<std::size_t>(mesh.triangles(f, 1)),
                     static_cast<std::size_t>(mesh.triangles(f, 2))});
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) PMP::orient_polygon_soup(points, faces);
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, faces, sm);
  return sm;
}

}  // namespace

namespace {

// The sign of orient3d(a, b, c, d) = (b - a) · ((c - a) × (d - a)) when double arithmetic
// certifies it, 0 when it cannot (then the exact predicate decides). Error bound: each
// difference is off by at most ε·M (M the largest coordinate magnitude), each of the six triple
// products by a few ε of L²(M + L) (L the longest difference); 100 ε L² (M + L) covers both
// with room.
int certainOrientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d) {
  const Eigen::Vector3d u = b - a, v = c - a, w = d - a;
  const double det = u.dot(v.cross(w));
  const double L =
      std::max({u.cwiseAbs().maxCoeff(), v.cwiseAbs().maxCoeff(), w.cwiseAbs().maxCoeff()});
  const double M = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(),
                             c.cwiseAbs().maxCoeff(), d.cwiseAbs().maxCoeff()});
  const double bound = 100.0 * std::numeric_limits<double>::epsilon() * L * L * (M + L);
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

Point point(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }

// Within a plane of normal n (a face's, not normalised), the side of the line through v along e
// that x lies on: the sign of n · (e × (x − v)) when double arithmetic certifies it, else 0. The
// two cross products are each off by a few ε of L (M + L) times their other factor, so that
// 100 ε L³ (M + L) bounds the error (L the longest of e, x − v and the sides behind n, M the
// largest coordinate).
int certainSide(const Eigen::Vector3d& n, double nScale, const Eigen::Vector3d& v,
                const Eigen::Vector3d& e, const Eigen::Vector3d& x) {
  const Eigen::Vector3d w = x - v;
  const double value = n.dot(e.cross(w));
  const double L = std::max({nScale, e.cwiseAbs().maxCoeff(), w.cwiseAbs().maxCoeff()});
  const double M = std::max({v.cwiseAbs().maxCoeff(), x.cwiseAbs().maxCoeff()});
  const double bound = 100.0 * std::numeric_limits<double>::epsilon() * L * L * L * (M + L);
  return value > bound ? 1 : value < -bound ? -1 : 0;
}

// Whether faces f and g of a closed mesh intersect other than along what they share, as CGAL's
// does_self_intersect decides it (Polygon_mesh_processing/self_intersections.h,
// do_faces_intersect), with a double-arithmetic shortcut for the neighbours that certainly do not
// (most pairs the boxes give are neighbours; on the flat regions of CAD parts CGAL's filtered
// predicates fall back to exact arithmetic for them, which cost twice the whole read).
class FacePairTest {
 public:
  explicit FacePairTest(const TriangleMesh& mesh) : mesh_(mesh) {}

  bool intersect(Eigen::Index f, Eigen::Index g) const {
    int shared = 0, fs[3], gs[3];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (mesh_.triangles(f, i) != mesh_.triangles(g, j)) continue;
        fs[shared] = i;
        gs[shared] = j;
        ++shared;
      }
    }
    if (shared == 2) return edgeNeighboursOverlap(f, g, fs, gs);
    if (shared == 1) return vertexNeighboursIntersect(f, g, fs[0], gs[0]);
    if (shared == 3) return true;  // a duplicate face (the checks before drop none)
    if (separated(f, g) || separated(g, f)) return false;
    return CGAL::do_intersect(triangle(f), triangle(g));
  }

 private:
  Eigen::Vector3d corner(Eigen::Index f, int k) const { return mesh_.corner(f, k); }
  Kernel::Triangle_3 triangle(Eigen::Index f) const {
    return {point(corner(f, 0)), point(corner(f, 1)), point(corner(f, 2))};
  }
  static int other(const int* s) { return 3 - s[0] - s[1]; }

  // Faces without a common corner: g lies strictly on one side of f's plane, or (coplanar
  // faces of a flat region, whose boxes overlap often) strictly beyond the line of one of f's
  // edges, on the side away from f. The separating-axis test for two triangles in a plane
  // needs only their edges' lines; checked both ways by the caller.
  bool separated(Eigen::Index f, Eigen::Index g) const {
    const Eigen::Vector3d a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
    const Eigen::Vector3d q[3] = {corner(g, 0), corner(g, 1), corner(g, 2)};
    const int s0 = certainOrientation(a, b, c, q[0]);
    if (s0 != 0 && s0 == certainOrientation(a, b, c, q[1]) &&
        s0 == certainOrientation(a, b, c, q[2])) {
      return true;
    }
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double scale = std::max((b - a).cwiseAbs().maxCoeff(), (c - a).cwiseAbs().maxCoeff());
    const Eigen::Vector3d p[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& v = p[k];
      const Eigen::Vector3d e = p[(k + 1) % 3] - v;
      const int own = certainSide(n, scale, v, e, p[(k + 2) % 3]);
      if (own == 0) continue;
      if (certainSide(n, scale, v, e, q[0]) == -own && certainSide(n, scale, v, e, q[1]) == -own &&
          certainSide(n, scale, v, e, q[2]) == -own) {
        return true;
      }
    }
    return false;
  }

  // Sharing an edge, they intersect beyond it only when coplanar with their third corners on
  // the same side of the edge (folded onto each other).
  bool edgeNeighboursOverlap(Eigen::Index f, Eigen::Index g, const int* fs, const int* gs) const {
    const Eigen::Vector3d a = corner(f, fs[0]), b = corner(f, fs[1]);
    const Eigen::Vector3d p = corner(f, other(fs)), q = corner(g, other(gs));
    if (certainOrientation(a, b, p, q) != 0) return false;  // not coplanar
    // coplanar (a flat region): p and q on opposite sides of the edge's line, no overlap
    const Eigen::Vector3d n = (b - a).cross(p - a);
    const double scale = std::max((b - a).cwiseAbs().maxCoeff(), (p - a).cwiseAbs().maxCoeff());
    const int sp = certainSide(n, scale, a, b - a, p), sq = certainSide(n, scale, a, b - a, q);
    if (sp != 0 && sq != 0 && sp != sq) return false;
    const Point A = point(a), B = point(b), P = point(p), Q = point(q);
    return CGAL::coplanar(A, B, P, Q) && CGAL::coplanar_orientation(A, B, P, Q) == CGAL::POSITIVE;
  }

  // Sharing a corner v, they intersect beyond it when the edge of either opposite v meets the
  // other face. When both other corners of g lie strictly on one side of f's plane, g meets
  // that plane at v alone, and neither edge can meet the other face.
  bool vertexNeighboursIntersect(Eigen::Index f, Eigen::Index g, int fv, int gv) const {
    const Eigen::Vector3d v = corner(f, fv);
    const Eigen::Vector3d a = corner(f, (fv + 1) % 3), b = corner(f, (fv + 2) % 3);
    const Eigen::Vector3d c = corner(g, (gv + 1) % 3), d = corner(g, (gv + 2) % 3);
    const int sc = certainOrientation(v, a, b, c), sd = certainOrientation(v, a, b, d);
    if (sc != 0 && sc == sd) return false;
    const int sa = certainOrientation(v, c, d, a), sb = certainOrientation(v, c, d, b);
    if (sa != 0 && sa == sb) return false;
    if (separatedInPlane(v, a, b, c, d)) return false;
    const Kernel::Segment_3 ab(point(a), point(b)), cd(point(c), point(d));
    return CGAL::do_intersect(triangle(f), cd) || CGAL::do_intersect(triangle(g), ab);
  }

  // Coplanar faces (v, a, b) and (v, c, d) meet at v alone when a line through v along one of
  // their edges leaves one face on one side and the other strictly on the other (disjoint
  // wedges at v: the fan of triangles around a vertex of a flat region).
  static bool separatedInPlane(const Eigen::Vector3d& v, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                               const Eigen::Vector3d& d) {
    const Eigen::Vector3d n = (a - v).cross(b - v);
    const double scale = std::max((a - v).cwiseAbs().maxCoeff(), (b - v).cwiseAbs().maxCoeff());
    const auto splits = [&](const Eigen::Vector3d& e, const Eigen::Vector3d& own,
                            const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
      const int so = certainSide(n, scale, v, e - v, own);
      const int sx = certainSide(n, scale, v, e - v, x), sy = certainSide(n, scale, v, e - v, y);
      return so != 0 && sx == -so && sy == -so;
    };
    return splits(a, b, c, d) || splits(b, a, c, d) || splits(c, d, a, b) || splits(d, c, a, b);
  }

  const TriangleMesh& mesh_;
};

struct Found {};  // stops the box scan at the first pair

}  // namespace

std::optional<SelfIntersection> findSelfIntersection(const TriangleMesh& mesh) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Eigen::Index>;
  std::vector<Box> boxes;
  boxes.reserve(static_cast<std::size_t>(mesh.triangleCount()));
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    const Point a = point(mesh.corner(f, 0)), b = point(mesh.corner(f, 1)),
                c = point(mesh.corner(f, 2));
    boxes.emplace_back(a.bbox() + b.bbox() + c.bbox(), f);
  }
  const FacePairTest test(mesh);
  std::optional<SelfIntersection> found;
  try {
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
      if (!test.intersect(x.info(), y.info())) return;
      SelfIntersection s;
      s.face_a = std::min(x.info(), y.info());
      s.face_b = std::max(x.info(), y.info());
      s.at = mesh.corner(s.face_a, 0);
      found = s;
      throw Found{};
    });
  } catch (const Found&) {
  }
  return found;
}

std::string removeSelfIntersections(TriangleMesh& mesh) {
  SurfaceMesh sm = toSurface(mesh);
  if (!PMP::does_self_intersect(sm)) return "";
  const std::size_t before = sm.number_of_faces();
  // CGAL 5.5's autorefinement refuses some configurations ("Non-handled triple intersection of
  // input triangles": three faces through one point, coplanar overlaps) by throwing.
  std::string why;
  try {
    if (!PMP::experimental::autorefine_and_remove_self_intersections(sm)) why = "not every one";
  } catch (const std::exception& e) {
    why = e.what();
  }
  if (why.empty() && (PMP::does_self_intersect(sm) || !CGAL::is_closed(sm))) {
    why = "the result is not a closed surface without intersections";
  }
  if (!why.empty()) {
    throw InputError("",
                     "the surface passes through itself and CGAL's autorefinement could not "
                     "remove the intersections (" +
                         why +
                         "); repair it in a mesh editor (MeshLab: Filters > Cleaning and "
                         "Repairing > Select Self Intersecting Faces, then delete them and close "
                         "the holes; Blender: 3D-Print toolbox > Intersections) or export it "
                         "again from the CAD model");
  }
  mesh = detail::toTriangleMesh(sm);
  std::ostringstream os;
  os << "removed the surface's self-intersections (cut " << before
     << " faces along them and kept the outer layer: " << mesh.triangleCount() << " faces)";
  return os.str();
}

}  // namespace vcontact::geometry
