#pragma once
// Simbody's ElasticFoundationForce on two copies of one mesh, A on a Free mobilizer and B fixed
// at the identity, behind a seam of plain arrays (simbody_pair.cpp is compiled as C++17).

#include <array>
#include <memory>
#include <vector>

namespace vcontact::bench {

class SimbodyPair {
 public:
  /// The mesh as x, y, z per vertex and three vertex indices per triangle (outward); k the
  /// elastic foundation's stiffness on each of the two meshes, N/m³ (f = k·a·x per face).
  SimbodyPair(const std::vector<double>& vertices, const std::vector<int>& triangles, double k);
  ~SimbodyPair();
  /// The contact force on A, N (world), with A at rotation R_WA (row-major) and origin p_WA:
  /// A's pose set, the system realised to Dynamics.
  std::array<double, 3> force(const std::array<double, 9>& R_WA, const std::array<double, 3>& p_WA);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vcontact::bench
