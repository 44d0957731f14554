#include "geometry/mesh_repair.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>

#include <array>
#include <cassert>
#include <cmath>
#include <functional>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>

#include "geometry/cgal_surface_internal.hpp"
#include "geometry/error.hpp"
#include "geometry/mass_properties.hpp"
#include "geometry/self_intersection.hpp"

namespace vcontact::geometry {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = detail::CgalSurface;
using detail::toTriangleMesh;
using Face = SurfaceMesh::Face_index;
using Halfedge = SurfaceMesh::Halfedge_index;
using Polygons = std::vector<std::vector<std::size_t>>;

std::string at(const Point& p) {
  std::ostringstream os;
  os.precision(9);
  os << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return os.str();
}

std::string count(std::size_t n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

struct Soup {
  std::vector<Point> points;
  Polygons polygons;
};

Soup toSoup(const TriangleMesh& mesh) {
  Soup s;
  for (Eigen::Index i = 0; i < mesh.vertexCount(); ++i) {
    s.points.emplace_back(mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2));
  }
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    s.polygons.push_back({static_cast<std::size_t>(mesh.triangles(f, 0)),
                          static_cast<std::size_t>(mesh.triangles(f, 1)),
                          static_cast<std::size_t>(mesh.triangles(f, 2))});
  }
  return s;
}

// Step 1. Each point takes the place of the first point (in file order) within `tolerance`
// of it that is not itself moved; CGAL's kd-tree finds the neighbours.
void weldClosePoints(Soup& s, double tolerance, std::vector<std::string>& changes) {
  using BaseTraits = CGAL::Search_traits_3<Kernel>;
  using PointMap = CGAL::Pointer_property_map<Point>::const_type;
  using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, BaseTraits>;
  using Tree = CGAL::Kd_tree<Traits>;
  const std::vector<Point> original = s.points;
  std::vector<std::size_t> ids(original.size());
  std::iota(ids.begin(), ids.end(), std::size_t{0});
  Tree tree(ids.begin(), ids.end(), Tree::Splitter(), Traits(CGAL::make_property_map(original)));
  constexpr std::size_t kFree = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> target(original.size(), kFree);
  std::size_t moved = 0, first = kFree;
  double largest = 0.0;
  for (std::size_t i = 0; i < original.size(); ++i) {
    if (target[i] != kFree) continue;
    target[i] = i;
    std::vector<std::size_t> near;
    tree.search(std::back_inserter(near),
                CGAL::Fuzzy_sphere<Traits>(original[i], tolerance, 0.0, tree.traits()));
    for (const std::size_t j : near) {
      if (target[j] != kFree) continue;
      target[j] = i;
      s.points[j] = original[i];
      largest = std::max(largest, std::sqrt(CGAL::squared_distance(original[i], original[j])));
      if (moved++ == 0) first = j;
    }
  }
  PMP::merge_duplicate_points_in_polygon_soup(s.points, s.polygons);
  if (moved == 0) return;
  std::ostringstream os;
  os.precision(3);
  os << "welded " << count(moved, "vertex", "vertices") << " onto a neighbour closer than "
     << tolerance << " m (largest gap " << largest << " m); first at " << at(original[first]);
  changes.push_back(os.str());
}

// The first polygon for which `bad` holds, or polygons.size().
std::size_t firstPolygon(const Polygons& polygons,
                         const std::function<bool(const std::vector<std::size_t>&)>& bad) {
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    if (bad(polygons[i])) return i;
  }
  return polygons.size();
}

// Step 2.
void dropDuplicateAndCollapsedFaces(Soup& s, std::vector<std::string>& changes) {
  std::set<std::vector<std::size_t>> seen;
  const std::size_t firstDuplicate = firstPolygon(s.polygons, [&](auto p) {
    std::sort(p.begin(), p.end());
    return !seen.insert(p).second;
  });
  const std::size_t firstCollapsed = firstPolygon(s.polygons, [](auto p) {
    std::sort(p.begin(), p.end());
    return std::adjacent_find(p.begin(), p.end()) != p.end();
  });
  const Point duplicateAt = firstDuplicate < s.polygons.size()
                                ? s.points[s.polygons[firstDuplicate][0]]
                                : Point(CGAL::ORIGIN);
  const Point collapsedAt = firstCollapsed < s.polygons.size()
                                ? s.points[s.polygons[firstCollapsed][0]]
                                : Point(CGAL::ORIGIN);
  const std::size_t duplicates =
      PMP::merge_duplicate_polygons_in_polygon_soup(s.points, s.polygons);
  const std::size_t before = s.polygons.size();
  PMP::repair_polygon_soup(s.points, s.polygons);
  const std::size_t collapsed = before - s.polygons.size();
  if (duplicates > 0) {
    changes.push_back("dropped " + count(duplicates, "duplicate face", "duplicate faces") +
                      "; first at " + at(duplicateAt));
  }
  if (collapsed > 0) {
    changes.push_back(
        "dropped " +
        count(collapsed, "face with a repeated corner", "faces with a repeated corner") +
        "; first at " + at(collapsedAt));
  }
}

Kernel::Vector_3 normal(const Soup& s, const std::vector<std::size_t>& p) {
  return CGAL::cross_product(s.points[p[1]] - s.points[p[0]], s.points[p[2]] - s.points[p[0]]);
}

// Step 3.
void orientSoup(Soup& s, std::vector<std::string>& changes) {
  const Soup before = s;
  const std::size_t pointsBefore = s.points.size();
  PMP::orient_polygon_soup(s.points, s.polygons);
  std::size_t reversed = 0, first = 0;
  for (std::size_t i = 0; i < s.polygons.size(); ++i) {
    if (normal(before, before.polygons[i]) * normal(s, s.polygons[i]) < 0.0) {
      if (reversed++ == 0) first = i;
    }
  }
  if (reversed > 0) {
    changes.push_back("reversed " + count(reversed, "face", "faces") +
                      " to orient the faces consistently; first at " +
                      at(s.points[s.polygons[first][0]]));
  }
  if (s.points.size() > pointsBefore) {
    changes.push_back("split " + count(s.points.size() - pointsBefore, "vertex", "vertices") +
                      " shared by surfaces that touch at one point only");
  }
}

SurfaceMesh toSurfaceMesh(const Soup& s) {
  if (!PMP::is_polygon_soup_a_polygon_mesh(s.polygons)) {
    throw InputError("", "faces do not form a surface even after orienting them");
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(s.points, s.polygons, sm);
  return sm;
}

std::vector<Halfedge> borderHalfedges(const SurfaceMesh& sm) {
  std::vector<Halfedge> out;
  for (const auto h : sm.halfedges()) {
    if (sm.is_border(h)) out.push_back(h);
  }
  return out;
}

// Step 4.
void stitch(SurfaceMesh& sm, std::vector<std::string>& changes) {
  const std::vector<Halfedge> border = borderHalfedges(sm);
  std::vector<Point> targets;
  for (const Halfedge h : border) targets.push_back(sm.point(sm.target(h)));
  const std::size_t stitched = PMP::stitch_borders(sm);
  if (stitched == 0) return;
  std::size_t first = 0;
  while (first + 1 < border.size() && !sm.is_removed(border[first]) &&
         sm.is_border(border[first])) {
    ++first;
  }
  changes.push_back("stitched " + count(stitched, "pair", "pairs") +
                    " of coincident border edges; first at " + at(targets[first]));
}

// Step 5.
void dropZeroAreaFaces(SurfaceMesh& sm, std::vector<std::string>& changes) {
  std::size_t degenerate = 0;
  Point first;
  for (const auto f : sm.faces()) {
    if (!PMP::is_degenerate_triangle_face(f, sm)) continue;
    if (degenerate++ == 0) first = sm.point(sm.target(sm.halfedge(f)));
  }
  if (degenerate == 0) return;
  PMP::remove_degenerate_faces(sm);
  changes.push_back("dropped " + count(degenerate, "zero-area face", "zero-area faces") +
                    " and re-stitched their neighbours; first at " + at(first));
}

double perimeter(const SurfaceMesh& sm, Halfedge border) {
  double length = 0.0;
  for (const auto h : CGAL::halfedges_around_face(border, sm)) {
    length += std::sqrt(CGAL::squared_distance(sm.point(sm.source(h)), sm.point(sm.target(h))));
  }
  return length;
}

// A hole whose boundary is planar (within kStripPlanarity of its size from its Newell plane)
// and strictly convex in that plane, filled by a strip zig-zagging between its two sides:
// corners (0, 1, n−1), (1, n−2, n−1), (1, 2, n−2), ... Any triangulation of an n-gon has
// n − 2 triangles, but the one CGAL's triangulate_hole gives a large cap is a fan of slivers
// from one corner, whose bounding boxes all overlap: the self-intersection tests of step 7
// and of checkShells then compare every pair, O(n²) exact coplanar tests (a 10,000-edge cap:
// minutes). A strip's boxes overlap only their neighbours'. Other holes go to CGAL.
constexpr double kStripPlanarity = 1e-9;

std::vector<std::array<std::size_t, 3>> convexStrip(const std::vector<Point>& p) {
  const std::size_t n = p.size();
  if (n < 4) return {};
  Kernel::Vector_3 normal(0, 0, 0);  // Newell: twice the area vector of the polygon
  for (std::size_t i = 0; i < n; ++i)
    normal = normal + CGAL::cross_product(p[i] - CGAL::ORIGIN, p[(i + 1) % n] - CGAL::ORIGIN);
  const double length = std::sqrt(normal.squared_length());
  if (!(length > 0.0)) return {};
  normal = normal / length;
  const CGAL::Bbox_3 box = CGAL::bbox_3(p.begin(), p.end());
  const double size =
      std::hypot(box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin());
  double turning = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs((p[i] - p[0]) * normal) > kStripPlanarity * size) return {};
    const Kernel::Vector_3 a = p[(i + 1) % n] - p[i], b = p[(i + 2) % n] - p[(i + 1) % n];
    const double sine = CGAL::cross_product(a, b) * normal, cosine = a * b;
    if (!(sine > kStripPlanarity * std::sqrt(a.squared_length() * b.squared_length()))) return {};
    turning += std::atan2(sine, cosine);
  }
  if (std::abs(turning - 2.0 * M_PI) > 1e-6) return {};  // winds once: a simple polygon
  std::vector<std::array<std::size_t, 3>> strip;
  std::size_t lo = 0, hi = n - 1;
  while (hi - lo >= 2) {
    strip.push_back({lo, lo + 1, hi});
    if (hi - lo >= 3) strip.push_back({lo + 1, hi - 1, hi});
    ++lo;
    --hi;
  }
  return strip;
}

// The hole of `border` filled by convexStrip; false, with the mesh unchanged, when it does
// not apply.
bool fillWithStrip(SurfaceMesh& sm, Halfedge border, std::vector<Face>& patch) {
  std::vector<SurfaceMesh::Vertex_index> corners;
  std::vector<Point> points;
  for (const auto h : CGAL::halfedges_around_face(border, sm)) {
    corners.push_back(sm.source(h));
    points.push_back(sm.point(sm.source(h)));
  }
  const std::vector<std::array<std::size_t, 3>> strip = convexStrip(points);
  if (strip.empty()) return false;
  for (const auto& t : strip) {
    const Face f = sm.add_face(corners[t[0]], corners[t[1]], corners[t[2]]);
    assert(f != SurfaceMesh::null_face());  // each triangle closes a corner of a simple hole
    patch.push_back(f);
  }
  return true;
}

// Step 6.
void fillSmallHoles(SurfaceMesh& sm, double diagonal, std::vector<std::string>& changes) {
  std::vector<Halfedge> cycles;
  PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
  const double largest = kSmallHolePerimeter * diagonal;
  std::size_t filled = 0, triangles = 0, left = 0;
  Point first;
  for (const Halfedge h : cycles) {
    if (perimeter(sm, h) > largest) {
      ++left;
      continue;
    }
    if (filled++ == 0) first = sm.point(sm.target(h));
    std::vector<Face> patch;
    if (!fillWithStrip(sm, h, patch)) PMP::triangulate_hole(sm, h, std::back_inserter(patch));
    triangles += patch.size();
  }
  std::ostringstream os;
  os.precision(3);
  if (filled > 0) {
    os << "filled " << count(filled, "hole", "holes") << " with "
       << count(triangles, "triangle", "triangles") << "; first at " << at(first);
    changes.push_back(os.str());
  }
  if (left > 0) {
    changes.push_back("left " + count(left, "hole", "holes") + " longer around than " +
                      std::to_string(largest) + " m unfilled");
  }
}

// Step 7. A shell inside no other must face outward. A shell inside another is left as it
// is: facing inward it is a cavity, facing outward checkShells refuses it, since which one the
// file meant cannot be told.
void turnOuterShellsOutward(SurfaceMesh& sm, std::vector<std::string>& changes) {
  if (!CGAL::is_closed(sm)) return;
  auto shellOf = sm.add_property_map<Face, std::size_t>("f:outer_shell", 0).first;
  auto volumeOf = sm.add_property_map<Face, std::size_t>("f:outer_volume", 0).first;
  std::vector<std::size_t> levels;
  std::vector<bool> outward;
  PMP::volume_connected_components(sm, volumeOf,
                                   CGAL::parameters::face_connected_component_map(shellOf)
                                       .nesting_levels(std::ref(levels))
                                       .is_cc_outward_oriented(std::ref(outward))
                                       .do_self_intersection_tests(true));
  std::vector<Face> inward;
  for (const auto f : sm.faces()) {
    const std::size_t shell = shellOf[f];
    if (shell < levels.size() && levels[shell] == 0 && !outward[shell]) inward.push_back(f);
  }
  sm.remove_property_map(shellOf);
  sm.remove_property_map(volumeOf);
  if (inward.empty()) return;
  PMP::reverse_face_orientations(inward, sm);
  changes.push_back("reversed " + count(inward.size(), "face", "faces") +
                    " of outer shells that faced inward; first at " +
                    at(sm.point(sm.target(sm.halfedge(inward.front())))));
}

// Faces joined across shared edges (union-find): the number of shells, without building a
// CGAL mesh, which costs more than all the other checks together on a one-shell part.
std::size_t countEdgeConnectedParts(const TriangleMesh& mesh) {
  std::vector<Eigen::Index> parent(static_cast<std::size_t>(mesh.triangleCount()));
  std::iota(parent.begin(), parent.end(), Eigen::Index{0});
  const auto root = [&](Eigen::Index f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  std::unordered_map<std::uint64_t, Eigen::Index> faceOfEdge;
  faceOfEdge.reserve(parent.size() * 3);
  std::size_t parts = parent.size();
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const auto [a, b] = std::minmax(mesh.triangles(f, k), mesh.triangles(f, (k + 1) % 3));
      const std::uint64_t edge =
          (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
      const auto [it, added] = faceOfEdge.emplace(edge, f);
      if (added) continue;
      const Eigen::Index r0 = root(f), r1 = root(it->second);
      if (r0 == r1) continue;
      parent[r0] = r1;
      --parts;
    }
  }
  return parts;
}

}  // namespace

RepairResult repairMesh(const TriangleMesh& soup, const RepairOptions& options) {
  const double diagonal = bounds(soup).size().norm();
  Soup s = toSoup(soup);
  RepairResult result;
  weldClosePoints(s, options.weldTolerance * diagonal, result.changes);
  dropDuplicateAndCollapsedFaces(s, result.changes);
  if (s.polygons.empty()) throw InputError("", "no face is left after repair");
  orientSoup(s, result.changes);
  SurfaceMesh sm = toSurfaceMesh(s);
  stitch(sm, result.changes);
  dropZeroAreaFaces(sm, result.changes);
  if (options.fillHoles) fillSmallHoles(sm, diagonal, result.changes);
  turnOuterShellsOutward(sm, result.changes);
  result.mesh = toTriangleMesh(sm);
  if (result.mesh.triangleCount() == 0) throw InputError("", "no face is left after repair");
  if (options.removeSelfIntersections && CGAL::is_closed(sm)) {
    const std::string change = removeSelfIntersections(result.mesh);
    if (!change.empty()) result.changes.push_back(change);
  }
  return result;
}

std::vector<Eigen::Vector3i> triangulatePolygon(const std::vector<Eigen::Vector3d>& corners) {
  std::vector<Point> points;
  Eigen::Vector3d newell = Eigen::Vector3d::Zero();  // twice the polygon's vector area
  for (std::size_t i = 0; i < corners.size(); ++i) {
    points.emplace_back(corners[i].x(), corners[i].y(), corners[i].z());
    newell += corners[i].cross(corners[(i + 1) % corners.size()]);
  }
  std::vector<CGAL::Triple<int, int, int>> patch;
  PMP::triangulate_hole_polyline(points, std::back_inserter(patch));
  std::vector<Eigen::Vector3i> out;
  for (const auto& t : patch) {
    Eigen::Vector3i f(t.first, t.second, t.third);
    const Eigen::Vector3d n = (corners[f[1]] - corners[f[0]]).cross(corners[f[2]] - corners[f[0]]);
    if (n.dot(newell) < 0.0) std::swap(f[1], f[2]);
    out.push_back(f);
  }
  if (out.empty()) throw InputError("", "a polygon face cannot be split into triangles");
  return out;
}

namespace {

// One shell's own intersection, which volume_connected_components (below, for several shells)
// looks for but a single shell never reached (issue 36).
void checkOneShell(const TriangleMesh& mesh) {
  const std::optional<SelfIntersection> s = findSelfIntersection(mesh);
  if (!s) return;
  std::ostringstream os;
  os.precision(9);
  os << "the surface passes through itself (faces " << s->face_a << " and " << s->face_b
     << " intersect; first at (" << s->at.x() << ", " << s->at.y() << ", " << s->at.z()
     << ")): its volume, centroid and inertia would be wrong; " << kSelfIntersectionHint;
  throw InputError("", os.str());
}

}  // namespace

std::size_t checkShells(const TriangleMesh& mesh) {
  if (countEdgeConnectedParts(mesh) == 1) {
    checkOneShell(mesh);
    return 1;
  }
  Soup s = toSoup(mesh);
  if (!PMP::is_polygon_soup_a_polygon_mesh(s.polygons)) {
    PMP::orient_polygon_soup(s.points, s.polygons);  // splits vertices where shells touch
  }
  SurfaceMesh sm = toSurfaceMesh(s);
  auto shellOf = sm.add_property_map<Face, std::size_t>("f:shell", 0).first;
  const std::size_t shells = PMP::connected_components(sm, shellOf);
  auto volumeOf = sm.add_property_map<Face, std::size_t>("f:volume", 0).first;
  std::vector<PMP::Volume_error_code> codes;
  PMP::volume_connected_components(
      sm, volumeOf,
      CGAL::parameters::do_self_intersection_tests(true).error_codes(std::ref(codes)));
  for (const auto f : sm.faces()) {
    const std::string where = "; first at " + at(sm.point(sm.target(sm.halfedge(f))));
    switch (codes[volumeOf[f]]) {
      case PMP::VALID_VOLUME:
        continue;
      case PMP::VOLUME_INTERSECTION:
        throw InputError("",
                         "closed shells intersect or touch each other (their volumes would "
                         "be added twice where they overlap); " +
                             count(shells, "shell", "shells") + where);
      case PMP::INCOMPATIBLE_ORIENTATION:
        throw InputError("",
                         "a closed shell lies inside another with the same orientation "
                         "(their volumes would be added: a cavity must face inward); " +
                             count(shells, "shell", "shells") + where);
      case PMP::SURFACE_WITH_SELF_INTERSECTIONS:
        throw InputError("", "a closed shell intersects itself; " +
                                 count(shells, "shell", "shells") + where + "; " +
                                 kSelfIntersectionHint);
    }
  }
  return shells;
}

}  // namespace vcontact::geometry
