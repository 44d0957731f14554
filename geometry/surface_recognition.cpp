#include "geometry/surface_recognition.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "geometry/error.hpp"
#include "geometry/surface_recognition_internal.hpp"

namespace vcontact::geometry {
namespace detail {

std::vector<Eigen::Vector3d> faceNormals(const TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d> n(static_cast<std::size_t>(mesh.triangleCount()));
  for (Eigen::Index f = 0; f < mesh.triangleCount(); ++f) {
    const Eigen::Vector3d c =
        (mesh.corner(f, 1) - mesh.corner(f, 0)).cross(mesh.corner(f, 2) - mesh.corner(f, 0));
    n[static_cast<std::size_t>(f)] = c.norm() > 0.0 ? c.normalized() : Eigen::Vector3d::Zero();
  }
  return n;
}

namespace {

// The angle of face f at its corner on vertex v.
double cornerAngle(const TriangleMesh& mesh, int f, int v) {
  int k = 0;
  while (mesh.triangles(f, k) != v) ++k;
  const Eigen::Vector3d p = mesh.corner(f, k);
  const Eigen::Vector3d a = mesh.corner(f, (k + 1) % 3) - p;
  const Eigen::Vector3d b = mesh.corner(f, (k + 2) % 3) - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Union–find root over the few faces around one vertex.
int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<int> smoothRegions(const TriangleMesh& mesh, const MeshTopology& topology,
                               const std::vector<Eigen::Vector3d>& face_normals, double cos_crease,
                               const std::vector<int>* taken) {
  std::vector<int> parent(static_cast<std::size_t>(mesh.triangleCount()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto free = [&](int f) { return taken == nullptr || (*taken)[f] < 0; };
  for (const MeshEdge& e : topology.edges())
    if (free(e.tri[0]) && free(e.tri[1]) &&
        face_normals[e.tri[0]].dot(face_normals[e.tri[1]]) >= cos_crease)
      parent[root(parent, e.tri[0])] = root(parent, e.tri[1]);
  for (std::size_t f = 0; f < parent.size(); ++f) parent[f] = root(parent, static_cast<int>(f));
  return parent;
}

namespace {

// Four samples inside each face of a smooth region with fewer than kFewSamples corner
// samples (a box face has 4; CGAL accepts no shape of fewer than 10 points): the centroid and
// the points at (4, 1, 1)/6 of the way to each corner, normals interpolated linearly. Larger
// regions get none, since RANSAC's time grows with the samples and their vertices suffice.
void addFaceSamples(const TriangleMesh& mesh, const std::vector<int>& region,
                    const std::vector<int>& corner_sample, SamplePoints& out) {
  constexpr std::size_t kFewSamples = 16;
  std::vector<std::vector<int>> corners(region.size());
  for (std::size_t f = 0; f < region.size(); ++f)
    for (int k = 0; k < 3; ++k) corners[region[f]].push_back(corner_sample[3 * f + k]);
  std::vector<char> few(region.size(), 0);
  for (std::size_t r = 0; r < corners.size(); ++r) {
    if (corners[r].empty()) continue;
    std::sort(corners[r].begin(), corners[r].end());
    few[r] = std::unique(corners[r].begin(), corners[r].end()) - corners[r].begin() <
             static_cast<std::ptrdiff_t>(kFewSamples);
  }
  static constexpr double kWeights[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3},
                                            {4.0 / 6, 1.0 / 6, 1.0 / 6},
                                            {1.0 / 6, 4.0 / 6, 1.0 / 6},
                                            {1.0 / 6, 1.0 / 6, 4.0 / 6}};
  for (int f = 0; f < static_cast<int>(mesh.triangleCount()); ++f) {
    const int* c = &corner_sample[3 * static_cast<std::size_t>(f)];
    if (!few[region[f]] || c[0] < 0 || c[1] < 0 || c[2] < 0) continue;
    for (const auto& w : kWeights) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        p += w[k] * mesh.corner(f, k);
        n += w[k] * out.normal[static_cast<std::size_t>(c[k])];
      }
      if (!(n.norm() > 0.0)) continue;
      out.position.push_back(p);
      out.normal.push_back(n.normalized());
      out.vertex.push_back(-1);
      out.face.push_back(f);
    }
  }
}

}  // namespace

SamplePoints samplePoints(const TriangleMesh& mesh, const MeshTopology& topology,
                          const std::vector<Eigen::Vector3d>& face_normals, double crease_angle) {
  const double cos_crease = std::cos(crease_angle);
  SamplePoints out;
  std::vector<int> corner_sample(3 * static_cast<std::size_t>(mesh.triangleCount()), -1);
  std::vector<int> parent;
  std::vector<Eigen::Vector3d> sum;
  for (int v = 0; v < static_cast<int>(mesh.vertexCount()); ++v) {
    const int* faces = topology.facesBegin(v);
    const int count = static_cast<int>(topology.facesEnd(v) - faces);
    const auto local = [&](int f) {
      return static_cast<int>(std::find(faces, faces + count, f) - faces);
    };
    parent.resize(static_cast<std::size_t>(count));
    std::iota(parent.begin(), parent.end(), 0);
    for (const int* e = topology.edgesBegin(v); e != topology.edgesEnd(v); ++e) {
      const MeshEdge& edge = topology.edges()[static_cast<std::size_t>(*e)];
      const Eigen::Vector3d& n0 = face_normals[static_cast<std::size_t>(edge.tri[0])];
      const Eigen::Vector3d& n1 = face_normals[static_cast<std::size_t>(edge.tri[1])];
      if (n0.dot(n1) >= cos_crease)
        parent[root(parent, local(edge.tri[0]))] = root(parent, local(edge.tri[1]));
    }
    sum.assign(static_cast<std::size_t>(count), Eigen::Vector3d::Zero());
    for (int i = 0; i < count; ++i)  // each side's angle-weighted normal
      sum[root(parent, i)] += cornerAngle(mesh, faces[i], v) * face_normals[faces[i]];
    std::vector<int> side_sample(static_cast<std::size_t>(count), -1);
    for (int i = 0; i < count; ++i) {
      if (root(parent, i) != i || !(sum[i].norm() > 0.0)) continue;
      side_sample[i] = static_cast<int>(out.position.size());
      out.position.push_back(mesh.vertex(v));
      out.normal.push_back(sum[i].normalized());
      out.vertex.push_back(v);
      out.face.push_back(faces[i]);
    }
    for (int i = 0; i < count; ++i) {
      int k = 0;
      while (mesh.triangles(faces[i], k) != v) ++k;
      corner_sample[3 * static_cast<std::size_t>(faces[i]) + k] = side_sample[root(parent, i)];
    }
  }
  addFaceSamples(mesh, smoothRegions(mesh, topology, face_normals, cos_crease), corner_sample, out);
  return out;
}

}  // namespace detail

namespace {

// RANSAC's distance, of the diagonal: RANSAC only proposes, the polish and the tolerance decide.
constexpr double kRansacEpsilon = 1e-3;
// Samples more than 1.5 longest edges apart are not one connected surface.
constexpr double kClusterEdges = 1.5;
// RANSAC keeps the shape that takes the most samples, and a rejected candidate's samples are
// lost to that run: near a corner of a box a wide cone takes more than a face's plane, and the
// rims of a frustum are matched by a torus that they do not fix (polishSurface refuses it).
// So the faces a run leaves free are searched again: with every kind but the torus (the most
// parameters), then for planes alone, then with every kind once more.
constexpr unsigned kAllKinds = 0x1f;
constexpr unsigned kPasses[] = {kAllKinds,
                                kAllKinds & ~(1u << static_cast<int>(SurfaceKind::kTorus)),
                                1u << static_cast<int>(SurfaceKind::kPlane), kAllKinds};

struct RecognitionInput {
  const TriangleMesh& mesh;
  std::vector<Eigen::Vector3d> normals;  // per face
  double tolerance;                      // m
  double cos_crease;
};

double faceArea(const TriangleMesh& mesh, int f) {
  return 0.5 * (mesh.corner(f, 1) - mesh.corner(f, 0))
                   .cross(mesh.corner(f, 2) - mesh.corner(f, 0))
                   .norm();
}

Eigen::Vector3d faceCentroid(const TriangleMesh& mesh, int f) {
  return (mesh.corner(f, 0) + mesh.corner(f, 1) + mesh.corner(f, 2)) / 3.0;
}

// The free faces that lie on `s`: their corners within the tolerance and their normal within
// the crease angle of the surface's.
std::vector<int> facesOn(const RecognisedSurface& s, const RecognitionInput& in,
                         const std::vector<int>& face_surface) {
  std::vector<int> faces;
  for (int f = 0; f < static_cast<int>(in.mesh.triangleCount()); ++f) {
    if (face_surface[f] >= 0 || !(in.normals[f].norm() > 0.0)) continue;
    bool on = in.normals[f].dot(outwardNormal(s, faceCentroid(in.mesh, f))) >= in.cos_crease;
    for (int k = 0; k < 3 && on; ++k)
      on = std::abs(signedDistance(s, in.mesh.corner(f, k))) <= in.tolerance;
    if (on) faces.push_back(f);
  }
  return faces;
}

std::vector<int> verticesOf(const TriangleMesh& mesh, const std::vector<int>& faces) {
  std::vector<int> v;
  for (int f : faces)
    for (int k = 0; k < 3; ++k) v.push_back(mesh.triangles(f, k));
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

std::vector<Eigen::Vector3d> positions(const TriangleMesh& mesh, const std::vector<int>& vertices) {
  std::vector<Eigen::Vector3d> p;
  p.reserve(vertices.size());
  for (int v : vertices) p.push_back(mesh.vertex(v));
  return p;
}

// The cylinder about a cone's axis through `points`, at their mean distance from it. RANSAC
// proposes a cone of a tiny angle for the vertices of a cylinder as readily as the cylinder
// (a capsule's band of one ring of faces, seen first as a cone, took every sample and failed
// to polish: its apex runs off to infinity), so a cone that does not polish is tried as this.
RecognisedSurface cylinderAlong(const RecognisedSurface& cone,
                                const std::vector<Eigen::Vector3d>& points) {
  RecognisedSurface s;
  s.kind = SurfaceKind::kCylinder;
  s.axis = cone.axis;
  s.point = cone.point;
  s.convex = cone.convex;
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d w = p - s.point;
    sum += (w - w.dot(s.axis) * s.axis).norm();
  }
  s.radius = sum / static_cast<double>(std::max<std::size_t>(points.size(), 1));
  return s;
}

// RANSAC's rough surface polished to its vertices, then again to those of them that lie on
// it (RANSAC's loose distance lets in neighbours of other surfaces).
std::optional<RecognisedSurface> polishCandidate(const detail::Candidate& c,
                                                 const detail::SamplePoints& samples,
                                                 const RecognitionInput& in) {
  std::vector<int> vertices;
  for (int i : c.samples)
    if (samples.vertex[static_cast<std::size_t>(i)] >= 0) vertices.push_back(samples.vertex[i]);
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  std::vector<Eigen::Vector3d> points = positions(in.mesh, vertices);
  std::optional<RecognisedSurface> first = detail::polishSurface(c.surface, points);
  if (!first && c.surface.kind == SurfaceKind::kCone)
    first = detail::polishSurface(cylinderAlong(c.surface, points), points);
  if (!first) return std::nullopt;
  const RecognisedSurface& s = *first;
  std::vector<double> d;
  for (const Eigen::Vector3d& p : points) d.push_back(std::abs(signedDistance(s, p)));
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double keep = std::max(in.tolerance, 3.0 * sorted[sorted.size() / 2]);
  std::vector<Eigen::Vector3d> close;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (d[i] <= keep) close.push_back(points[i]);
  return detail::polishSurface(s, close);
}

// The direction in which `points` spread least: the axis of full or half rings of a sphere's
// zone, whose heights differ less than their radii.
Eigen::Vector3d leastSpread(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) spread += (p - mean) * (p - mean).transpose();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(spread).eigenvectors().col(0);
}

// Vertices on two circles about the axis `a` through `centre` lie on the cone (or the
// cylinder) through those circles: the circles are the two heights along `a`; the cone or
// cylinder through them is then polished to the vertices. None unless the vertices form
// exactly two rings of three or more and the result holds every one of them within the
// tolerance.
std::optional<RecognisedSurface> ruledThroughTwoRings(const Eigen::Vector3d& centre,
                                                      const Eigen::Vector3d& a, bool convex,
                                                      const std::vector<Eigen::Vector3d>& points,
                                                      double tolerance) {
  std::vector<std::pair<double, double>> zr;  // (height along a from the centre, radius)
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d w = p - centre;
    zr.emplace_back(w.dot(a), (w - w.dot(a) * a).norm());
  }
  std::sort(zr.begin(), zr.end());
  std::vector<std::size_t> starts{0};
  for (std::size_t i = 1; i < zr.size(); ++i)
    if (zr[i].first - zr[i - 1].first > tolerance) starts.push_back(i);
  if (starts.size() != 2 || starts[1] < 3 || zr.size() - starts[1] < 3) return std::nullopt;
  double z[2] = {0.0, 0.0}, r[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const std::size_t end = k ? zr.size() : starts[1];
    for (std::size_t i = starts[k]; i < end; ++i) z[k] += zr[i].first, r[k] += zr[i].second;
    z[k] /= static_cast<double>(end - starts[k]);
    r[k] /= static_cast<double>(end - starts[k]);
  }
  RecognisedSurface start;
  start.convex = convex;
  if (std::abs(r[1] - r[0]) <= tolerance) {
    start.kind = SurfaceKind::kCylinder;
    start.point = centre + 0.5 * (z[0] + z[1]) * a;
    start.axis = a;
    start.radius = 0.5 * (r[0] + r[1]);
  } else {  // r grows with z along +a when k > 0; the apex is where r reaches 0
    const double k = (r[1] - r[0]) / (z[1] - z[0]);
    start.kind = SurfaceKind::kCone;
    start.point = centre + (z[0] - r[0] / k) * a;
    start.axis = k > 0.0 ? a : Eigen::Vector3d(-a);
    start.angle = std::atan(std::abs(k));
  }
  std::optional<RecognisedSurface> ruled = detail::polishSurface(start, points);
  if (!ruled) return std::nullopt;
  for (const Eigen::Vector3d& p : points)
    if (!(std::abs(signedDistance(*ruled, p)) <= tolerance)) return std::nullopt;
  return ruled;
}

// The sum of squared distances to `s` of the midpoints of the faces' edges that join the two
// rings (whose ends differ in height along `axis` by more than `tolerance`). An edge within a
// ring is a chord of a circle both surfaces hold, and says nothing of the meridian.
double edgeMidpointResidual(const RecognisedSurface& s, const TriangleMesh& mesh,
                            const std::vector<int>& faces, const Eigen::Vector3d& axis,
                            double tolerance) {
  double sum = 0.0;  // an interior edge counts twice, once from each face: the same for both
  for (int f : faces)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = mesh.corner(f, k), b = mesh.corner(f, (k + 1) % 3);
      if (!(std::abs((b - a).dot(axis)) > tolerance)) continue;
      const double d = signedDistance(s, 0.5 * (a + b));
      sum += d * d;
    }
  return sum;
}

// The tie-break between a sphere and a cone or cylinder that both hold a region's vertices
// (docs/SURFACES.md, "Recognition"): the edges decide. A vertex tells only that the surface
// passes through it; an edge between two rings tells that the region is straight along it,
// which a cone or cylinder is along its rulings and a sphere is nowhere. The midpoints of the
// region's edges lie on the ruled surface along rulings and a chord's sagitta inside the
// sphere, so the surface with the smaller residual there is taken; it must also cover every
// face the sphere covered, so that the choice only renames the region. Only the edges between
// the two rings count: within a ring an edge is a chord of a circle on both.
void preferRuledSurface(RecognisedSurface& s, const RecognitionInput& in,
                        const std::vector<int>& face_surface) {
  const std::vector<Eigen::Vector3d> points = positions(in.mesh, verticesOf(in.mesh, s.faces));
  // A sphere's vertices on two coaxial circles lie as well on the cone or cylinder through them.
  std::optional<RecognisedSurface> ruled =
      ruledThroughTwoRings(s.point, leastSpread(points), s.convex, points, in.tolerance);
  if (!ruled) return;
  ruled->faces = facesOn(*ruled, in, face_surface);
  if (!std::includes(ruled->faces.begin(), ruled->faces.end(), s.faces.begin(), s.faces.end()))
    return;
  const auto residual = [&](const RecognisedSurface& t) {
    return edgeMidpointResidual(t, in.mesh, s.faces, ruled->axis, in.tolerance);
  };
  if (residual(*ruled) < residual(s)) s = std::move(*ruled);
}

void measure(RecognisedSurface& s, const TriangleMesh& mesh) {
  s.area = 0.0;
  for (int f : s.faces) s.area += faceArea(mesh, f);
  double sum2 = 0.0;
  s.max_residual = 0.0;
  const std::vector<int> vertices = verticesOf(mesh, s.faces);
  for (int v : vertices) {
    const double d = std::abs(signedDistance(s, mesh.vertex(v)));
    sum2 += d * d;
    s.max_residual = std::max(s.max_residual, d);
  }
  s.rms_residual = std::sqrt(sum2 / static_cast<double>(vertices.size()));
}

// The faces the passes left free, in smooth regions joined across their edges (ascending).
std::vector<std::vector<int>> freeRegions(const RecognitionInput& in, const MeshTopology& topology,
                                          const std::vector<int>& face_surface) {
  const std::vector<int> label =
      detail::smoothRegions(in.mesh, topology, in.normals, in.cos_crease, &face_surface);
  std::vector<int> region_of(face_surface.size(), -1);
  std::vector<std::vector<int>> regions;
  for (int f = 0; f < static_cast<int>(face_surface.size()); ++f) {
    if (face_surface[f] >= 0) continue;
    int& r = region_of[label[f]];
    if (r < 0) r = static_cast<int>(regions.size()), regions.emplace_back();
    regions[r].push_back(f);
  }
  return regions;
}

// A free region whose vertices are two coaxial rings, read as the cylinder or cone through
// them. It is what RANSAC misses on a band of one ring of faces between two recognised
// surfaces that it meets smoothly (a coarse capsule's cylinder between its hemispheres): the
// band's samples are its rims' vertices, whose normals are blends with the neighbours' faces,
// so no candidate drawn from them holds both rims. The axis is the direction the band's face
// normals spread least about their mean (a cylinder's are perpendicular to it, a cone's at
// one angle); the rims and the fit are ruledThroughTwoRings', and the surface must take
// every face of the region.
std::optional<RecognisedSurface> bandSurface(const std::vector<int>& region,
                                             const RecognitionInput& in,
                                             const std::vector<int>& face_surface) {
  if (region.size() < 3) return std::nullopt;
  std::vector<Eigen::Vector3d> normals;
  for (int f : region) normals.push_back(in.normals[f]);
  const Eigen::Vector3d axis = leastSpread(normals);
  const std::vector<Eigen::Vector3d> points = positions(in.mesh, verticesOf(in.mesh, region));
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centre += p;
  centre /= static_cast<double>(points.size());
  double outward = 0.0;  // convex when the faces face away from the axis
  for (int f : region) {
    const Eigen::Vector3d w = faceCentroid(in.mesh, f) - centre;
    outward += in.normals[f].dot(w - w.dot(axis) * axis);
  }
  std::optional<RecognisedSurface> ruled =
      ruledThroughTwoRings(centre, axis, outward >= 0.0, points, in.tolerance);
  if (!ruled) return std::nullopt;
  ruled->faces = facesOn(*ruled, in, face_surface);
  if (!std::includes(ruled->faces.begin(), ruled->faces.end(), region.begin(), region.end()))
    return std::nullopt;
  return ruled;
}

// The samples a pass may use: those of faces no surface has taken, and a vertex's sample
// wherever a face of its side is still free. A vertex on a smooth seam (a capsule's cylinder
// meeting its hemispheres tangentially) has one sample for all its faces, filed under one of
// them: were that face taken, the free faces across the seam would lose the sample, and a
// band of one ring of faces between two taken regions would have none left at all.
std::vector<char> freeSamples(const detail::SamplePoints& samples, const MeshTopology& topology,
                              const RecognitionInput& in, const std::vector<int>& face_surface) {
  std::vector<char> use(samples.face.size());
  for (std::size_t i = 0; i < use.size(); ++i) {
    use[i] = face_surface[samples.face[i]] < 0;
    const int v = samples.vertex[i];
    if (use[i] || v < 0) continue;
    for (const int* f = topology.facesBegin(v); f != topology.facesEnd(v) && !use[i]; ++f)
      use[i] = face_surface[*f] < 0 && in.normals[*f].dot(samples.normal[i]) >= in.cos_crease;
  }
  return use;
}

void checkOptions(const RecognitionOptions& o) {
  if (!(o.tolerance > 0.0 && o.tolerance < 1.0))
    throw InputError("surface recognition",
                     "the tolerance must be in (0, 1), a fraction of the "
                     "bounding-box diagonal");
  if (!(o.crease_angle > 0.0 && o.crease_angle <= M_PI / 2))
    throw InputError("surface recognition", "the crease angle must be in (0, pi/2] rad");
}

}  // namespace

SurfaceRecognition recogniseSurfaces(const TriangleMesh& mesh, const RecognitionOptions& options) {
  checkOptions(options);
  const MeshTopology topology(mesh);
  const double diagonal = bounds(mesh).size().norm();
  RecognitionInput in{mesh, detail::faceNormals(mesh), options.tolerance * diagonal,
                      std::cos(options.crease_angle)};
  const detail::SamplePoints samples =
      detail::samplePoints(mesh, topology, in.normals, options.crease_angle);
  double longest = 0.0;
  for (const MeshEdge& e : topology.edges())
    longest = std::max(longest, (mesh.vertex(e.v1) - mesh.vertex(e.v0)).norm());
  detail::DetectionSettings settings{kRansacEpsilon * diagonal, kClusterEdges * longest,
                                     std::cos(options.crease_angle), options.seed};

  SurfaceRecognition out;
  out.tolerance = in.tolerance;
  out.face_surface.assign(static_cast<std::size_t>(mesh.triangleCount()), -1);
  std::vector<RecognisedSurface> found;
  for (unsigned kinds : kPasses) {
    const std::vector<char> use = freeSamples(samples, topology, in, out.face_surface);
    settings.kinds = kinds;
    for (const detail::Candidate& c : detail::detectCandidates(samples, use, settings)) {
      std::optional<RecognisedSurface> polished = polishCandidate(c, samples, in);
      if (!polished) continue;
      RecognisedSurface& s = *polished;
      s.faces = facesOn(s, in, out.face_surface);
      if (s.faces.empty()) continue;
      if (s.kind == SurfaceKind::kSphere) preferRuledSurface(s, in, out.face_surface);
      measure(s, mesh);
      for (int f : s.faces) out.face_surface[f] = static_cast<int>(found.size());
      found.push_back(std::move(s));
    }
  }
  for (const std::vector<int>& region : freeRegions(in, topology, out.face_surface)) {
    std::optional<RecognisedSurface> band = bandSurface(region, in, out.face_surface);
    if (!band) continue;
    measure(*band, mesh);
    for (int f : band->faces) out.face_surface[f] = static_cast<int>(found.size());
    found.push_back(std::move(*band));
  }
  // Largest first; ties (by construction rare) keep RANSAC's order.
  std::vector<int> order(found.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return found[a].area > found[b].area; });
  std::vector<int> rank(found.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    rank[order[i]] = static_cast<int>(i);
    out.surfaces.push_back(std::move(found[order[i]]));
  }
  for (int& s : out.face_surface) {
    if (s >= 0) {
      s = rank[s];
      continue;
    }
    ++out.free_form_faces;
  }
  for (int f = 0; f < static_cast<int>(mesh.triangleCount()); ++f)
    if (out.face_surface[f] < 0) out.free_form_area += faceArea(mesh, f);
  return out;
}

}  // namespace vcontact::geometry
