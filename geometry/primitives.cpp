#include "geometry/primitives.hpp"

#include <cmath>
#include <sstream>

#include "geometry/error.hpp"

namespace vcontact::geometry {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

void requirePositive(double value, const char* what, const std::string& source) {
  if (!std::isfinite(value) || value <= 0.0) {
    std::ostringstream os;
    os << what << " must be a finite positive length in metres, got " << value;
    throw InputError(source, os.str());
  }
}

}  // namespace

std::string shapeKind(const Shape& shape) {
  return std::visit(Overloaded{[](const Sphere&) { return std::string("sphere"); },
                               [](const Cylinder&) { return std::string("cylinder"); },
                               [](const Box&) { return std::string("box"); },
                               [](const HalfSpace&) { return std::string("halfspace"); },
                               [](const Mesh&) { return std::string("mesh"); }},
                    shape);
}

std::string describe(const Shape& shape) {
  std::ostringstream os;
  os.precision(6);
  std::visit(
      Overloaded{[&](const Sphere& s) { os << "sphere R=" << s.radius; },
                 [&](const Cylinder& c) { os << "cylinder R=" << c.radius << " L=" << c.length; },
                 [&](const Box& b) {
                   os << "box " << b.size.x() << "x" << b.size.y() << "x" << b.size.z();
                 },
                 [&](const HalfSpace&) { os << "halfspace z<=0"; },
                 [&](const Mesh& m) {
                   os << "mesh " << m.name << " (" << m.mesh->triangleCount() << " triangles)";
                 }},
      shape);
  return os.str();
}

void validate(const Shape& shape, const std::string& source) {
  std::visit(
      Overloaded{[&](const Sphere& s) { requirePositive(s.radius, "sphere radius", source); },
                 [&](const Cylinder& c) {
                   requirePositive(c.radius, "cylinder radius", source);
                   requirePositive(c.length, "cylinder length", source);
                 },
                 [&](const Box& b) {
                   requirePositive(b.size.x(), "box size x", source);
                   requirePositive(b.size.y(), "box size y", source);
                   requirePositive(b.size.z(), "box size z", source);
                 },
                 [](const HalfSpace&) {},
                 [&](const Mesh& m) {
                   if (!m.mesh || m.mesh->triangleCount() == 0) {
                     throw InputError(source, "mesh has no triangles");
                   }
                 }},
      shape);
}

}  // namespace vcontact::geometry
