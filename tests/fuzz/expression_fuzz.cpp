// libFuzzer harness: the formulas of an expression effect (formats/expression_entry,
// dynamics/effects/expression). The bytes up to the first NUL are the normal term, to the next
// the tangential term, the rest the spin term (each may be empty); an effect that compiles is
// added to stiffness + coulomb and evaluated on one sliding, spinning contact, so muparser's
// bytecode runs too. A result that is not finite is an answer, not a finding.

#include <array>
#include <nlohmann/json.hpp>

#include "dynamics/model.hpp"
#include "formats/expression_entry.hpp"
#include "geometry/error.hpp"
#include "volume/contact_volume.hpp"

namespace {

std::array<std::string, 3> terms(const std::uint8_t* data, std::size_t size) {
  std::array<std::string, 3> t;
  std::size_t k = 0;
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == 0 && k < 2) {
      ++k;
      continue;
    }
    t[k] += static_cast<char>(data[i]);
  }
  return t;
}

void evaluate(std::unique_ptr<vcontact::dynamics::Effect> effect) {
  vcontact::dynamics::Model model =
      vcontact::dynamics::Model::withEffects({"stiffness", "coulomb"});
  model.add(std::move(effect));
  vcontact::volume::ContactVolume cv;
  cv.volume = 1e-12;
  cv.p_WC = Eigen::Vector3d(0, 0, -1e-5);
  cv.n_W = Eigen::Vector3d::UnitZ();
  cv.depth = 1e-5;
  cv.area = 1e-6;
  cv.r_gyr = 1e-3;
  cv.J_v = Eigen::Matrix3d::Identity() * 1e-18;
  cv.J_s = Eigen::Matrix3d::Identity() * 1e-12;
  vcontact::dynamics::RelativeMotion motion;
  motion.v_c_W = Eigen::Vector3d(1e-3, 0, -1e-4);
  motion.w_W = Eigen::Vector3d(0, 0, 0.5);
  model.evaluate(cv, motion, vcontact::dynamics::PairState{});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::array<std::string, 3> t = terms(data, size);
  nlohmann::json entry = {{"kind", "expression"},
                          {"parameters",
                           {{"b", {{"value", 0.5}, {"unit", "-"}, {"lower", -1}, {"upper", 1}}},
                            {"c2", {{"value", 2e-3}, {"unit", "-"}, {"lower", 0}, {"upper", 1}}}}},
                          {"requires", {"stiffness"}}};
  const char* keys[] = {"normal", "tangential", "spin"};
  for (int k = 0; k < 3; ++k) {
    if (!t[k].empty()) entry[keys[k]] = t[k];
  }
  try {
    evaluate(vcontact::formats::expressionEffectFromJson("fuzzed", entry, "fuzz.model.json",
                                                         "effects.fuzzed"));
  } catch (const vcontact::InputError&) {
  }
  return 0;
}
