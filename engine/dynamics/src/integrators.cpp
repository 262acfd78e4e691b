// The integrator catalog, the factory, and the Euler family.
//
// The Euler variants differ in what they evaluate where:
// - explicit-euler: everything from the old state, the rotation in the classic body-frame form
//   w_b += h J^-1 (tau_b - w_b x J w_b), which is what makes it blow up on gyroscopic
//   stiffness (the (w2, w3) rotation of a fast needle is amplified by sqrt(1 + (h w1)^2));
// - semi-implicit-euler: symplectic Euler in translation and rotation alike: kick v and world
//   L with the old forces, drift x with the new v, then the free rotation over h as the
//   Lie-Trotter product R1(h) R2(h) R3(h) of the exact flows of the three terms
//   L_i^2 / (2 J_i) of the kinetic energy (the first-order, non-symmetric sibling of the
//   splitting integrator's R1(h/2) R2(h/2) R3(h) R2(h/2) R1(h/2); Dullweber, Leimkuhler and
//   McLachlan 1997). A composition of exact Hamiltonian flows, hence symplectic: bounded
//   energy error, no drift; world L exact without torques;
// - lie-euler: what semi-implicit-euler used to be, kept for comparison: the same kick and
//   drift, then q <- exp(h w / 2) q with w = I_w^-1 L_new at the old orientation. A first-order
//   Lie-Euler step: world L exact without torques, but not symplectic in rotation (the
//   rotational energy depends on both q and L), so the energy drifts;
// - seed-semi-implicit: the note's angular update as written, w_{n+1} = w_n + h I_w^-1 tau,
//   with no gyroscopic term: world w is frozen without torques (order 0, for comparison only);
// - implicit-euler: backward Euler on the gyroscopic term in the body frame, solved by Newton
//   (Catto, "Numerical methods", GDC 2015): unconditionally stable, damps tumbling. Translation
//   is symplectic Euler, as in semi-implicit-euler (so the two agree on a pure spring).
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <Eigen/LU>

#include "base/errors.hpp"
#include "principal_rotation.hpp"
#include "steppers.hpp"

namespace tumble::engine {
namespace steppers {
namespace {

class ExplicitEuler final : public BodyStepper {
 public:
  explicit ExplicitEuler(const BodyModel& body) : body_(body) {}
  void step(BodyState& s, double, double h) override {
    const Rates r = rates(body_, s);
    // Euler's equations in the body frame, everything from the old state.
    const Eigen::Vector3d& J = body_.moments;
    const Eigen::Vector3d w_b = s.orientation.conjugate() * r.omega;
    const Eigen::Vector3d tau_b = s.orientation.conjugate() * r.torque;
    const Eigen::Vector3d w_b_new =
        w_b + h * (tau_b - w_b.cross(J.cwiseProduct(w_b))).cwiseQuotient(J);
    if (!body_.pivoted) {
      s.position += h * s.velocity;
      s.velocity += h * r.acceleration;
    }
    s.orientation = renormalized(s.orientation * rotation_quaternion(h * w_b));
    s.angular_momentum = s.orientation * J.cwiseProduct(w_b_new);
  }

 private:
  const BodyModel& body_;
};

/// Kick with the old forces (none evaluated for a body without force terms), then drift x
/// with the new v: the translational half of both semi-implicit-euler and lie-euler.
void kick_and_drift(const BodyModel& body, BodyState& s, double h) {
  if (!body.forces.empty()) {
    const Rates r = rates(body, s);
    s.angular_momentum += h * r.torque;
    s.velocity += h * r.acceleration;
  }
  if (!body.pivoted) s.position += h * s.velocity;
}

class SemiImplicitEuler final : public BodyStepper {
 public:
  explicit SemiImplicitEuler(const BodyModel& body)
      : body_(body), inverse_moments_(body.moments.cwiseInverse()) {}
  void step(BodyState& s, double, double h) override {
    kick_and_drift(body_, s, h);
    // R1(h) R2(h) R3(h): each an exact rotation about one principal axis by h L_i / J_i with
    // the body-frame momentum turning back; world L is not touched.
    Eigen::Vector3d momentum = s.orientation.conjugate() * s.angular_momentum;  // body frame
    Eigen::Vector4d q(s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z());
    for (int axis = 0; axis < 3; ++axis) {
      rotate_about_principal_axis(inverse_moments_, axis, h, q, momentum);
    }
    s.orientation = renormalized(Eigen::Quaterniond(q[0], q[1], q[2], q[3]));
  }

 private:
  const BodyModel& body_;
  Eigen::Vector3d inverse_moments_;
};

class LieEuler final : public BodyStepper {
 public:
  explicit LieEuler(const BodyModel& body) : body_(body) {}
  void step(BodyState& s, double, double h) override {
    kick_and_drift(body_, s, h);
    const Eigen::Vector3d omega = angular_velocity(body_, s);  // new L, old orientation
    s.orientation = renormalized(rotation_quaternion(h * omega) * s.orientation);
  }

 private:
  const BodyModel& body_;
};

class SeedSemiImplicit final : public BodyStepper {
 public:
  explicit SeedSemiImplicit(const BodyModel& body) : body_(body) {}
  void step(BodyState& s, double, double h) override {
    const Rates r = rates(body_, s);
    // The note: alpha = I_w^-1 tau, w += alpha h (I_w treated as constant: no gyroscopic term).
    const Eigen::Vector3d alpha =
        s.orientation * (s.orientation.conjugate() * r.torque).cwiseQuotient(body_.moments);
    const Eigen::Vector3d omega = r.omega + h * alpha;
    if (!body_.pivoted) {
      s.velocity += h * r.acceleration;
      s.position += h * s.velocity;
    }
    s.orientation = renormalized(rotation_quaternion(h * omega) * s.orientation);
    // Store the momentum that gives back this w in the new orientation: w stays frozen.
    s.angular_momentum =
        s.orientation * body_.moments.cwiseProduct(s.orientation.conjugate() * omega);
  }

 private:
  const BodyModel& body_;
};

class ImplicitEuler final : public BodyStepper {
 public:
  explicit ImplicitEuler(const BodyModel& body) : body_(body) {}
  void step(BodyState& s, double, double h) override {
    const Rates r = rates(body_, s);
    const Eigen::Vector3d& J = body_.moments;
    const Eigen::Vector3d w0 = s.orientation.conjugate() * r.omega;
    const Eigen::Vector3d tau_b = s.orientation.conjugate() * r.torque;
    // Newton on f(w) = J (w - w0) + h w x J w - h tau_b = 0, in the frame of the old orientation.
    Eigen::Vector3d w = w0;
    for (int iteration = 0; iteration < 30; ++iteration) {
      const Eigen::Vector3d Jw = J.cwiseProduct(w);
      const Eigen::Vector3d f = J.cwiseProduct(w - w0) + h * w.cross(Jw) - h * tau_b;
      const Eigen::Matrix3d jacobian = Eigen::Matrix3d(J.asDiagonal()) +
                                       h * (cross_matrix(w) * J.asDiagonal() - cross_matrix(Jw));
      const Eigen::Vector3d delta = jacobian.partialPivLu().solve(f);
      w -= delta;
      if (!(delta.norm() > 1e-15 * w.norm())) break;
    }
    if (!body_.pivoted) {
      s.velocity += h * r.acceleration;
      s.position += h * s.velocity;
    }
    s.orientation = renormalized(s.orientation * rotation_quaternion(h * w));
    s.angular_momentum = s.orientation * J.cwiseProduct(w);
  }

 private:
  const BodyModel& body_;
};

}  // namespace

std::unique_ptr<BodyStepper> make_explicit_euler(const BodyModel& body) {
  return std::make_unique<ExplicitEuler>(body);
}
std::unique_ptr<BodyStepper> make_semi_implicit_euler(const BodyModel& body) {
  return std::make_unique<SemiImplicitEuler>(body);
}
std::unique_ptr<BodyStepper> make_lie_euler(const BodyModel& body) {
  return std::make_unique<LieEuler>(body);
}
std::unique_ptr<BodyStepper> make_seed_semi_implicit(const BodyModel& body) {
  return std::make_unique<SeedSemiImplicit>(body);
}
std::unique_ptr<BodyStepper> make_implicit_euler(const BodyModel& body) {
  return std::make_unique<ImplicitEuler>(body);
}

}  // namespace steppers

const std::vector<IntegratorInfo>& integrator_catalog() {
  using K = IntegratorKind;
  // The last figure: right-hand-side evaluations per step (engine/PHYSICS.md §5): the force
  // evaluations with their rotational rate, counted as if the body had force terms (those
  // without skip the force code, not the count). Kicks are not shared between steps: a
  // splitting evaluates at both ends of each sub-step. implicit-euler's Newton solve reuses its
  // one evaluation; midpoint's figure is its least (two Newton iterations), but it counts its
  // own (one per iteration), as dopri does; exact evaluates none.
  static const std::vector<IntegratorInfo> catalog = {
      {K::kExplicitEuler, "explicit-euler", 1, false, false,
       "everything from the old state; energy grows, blows up on fast or extreme-ratio spins", 1},
      {K::kSemiImplicitEuler, "semi-implicit-euler", 1, false, false,
       "symplectic Euler in translation and rotation: kick v and L, drift x, then the "
       "principal-axis sub-rotations R1(h) R2(h) R3(h); bounded energy error, world L exact",
       1},
      {K::kLieEuler, "lie-euler", 1, false, false,
       "the former semi-implicit-euler: kick v and L, drift x, turn q by the new w at the old "
       "orientation; world L exact but the energy drifts; comparison only",
       1},
      {K::kSeedSemiImplicit, "seed-semi-implicit", 0, false, false,
       "the founding note's update as written, no gyroscopic term (engine/PHYSICS.md §2): no "
       "flip, no precession; comparison only",
       1},
      {K::kImplicitEuler, "implicit-euler", 1, false, false,
       "backward Euler on the gyroscopic term (Newton), symplectic Euler in translation; "
       "stable, damps tumbling",
       1},
      {K::kRk4, "rk4", 4, false, false,
       "classical RK4, Munthe-Kaas form on the rotation group (4th order in orientation too)", 4},
      {K::kMidpoint, "midpoint", 2, false, false,
       "implicit midpoint (Newton), symmetric; keeps energy, |L| and |q| of the free body "
       "exactly",
       2},
      {K::kSplitting, "splitting", 2, false, false,
       "explicit symplectic rotation splitting (Dullweber-Leimkuhler-McLachlan); world L exact", 2},
      {K::kSplitting4, "splitting4", 4, false, false,
       "4th-order Yoshida composition of splitting; symplectic, world L exact", 6},
      {K::kFreeRotor, "free-rotor", 2, false, false,
       "half kick, exact torque-free flow, half kick; exact without torques (gyroscopic tops)", 2},
      {K::kMoserVeselov, "moser-veselov", 2, false, false,
       "half kick, discrete Moser-Veselov step, half kick; symplectic, keeps world L and the "
       "free body's energy to rounding",
       2},
      {K::kDopri, "dopri", 5, true, false,
       "adaptive Dormand-Prince 5(4) with --tolerance; the reference for forced problems", 0},
      {K::kExact, "exact", -1, false, true,
       "closed form: torque-free bodies and heavy symmetric tops; refuses other forced bodies", 0},
  };
  return catalog;
}

const IntegratorInfo& integrator_info(IntegratorKind kind) {
  for (const IntegratorInfo& info : integrator_catalog()) {
    if (info.kind == kind) return info;
  }
  throw std::logic_error("integrator_info: unknown kind");
}

std::optional<IntegratorKind> integrator_from_name(std::string_view name) {
  for (const IntegratorInfo& info : integrator_catalog()) {
    if (info.name == name) return info.kind;
  }
  return std::nullopt;
}

std::optional<std::string> step_settings_problem(const StepSettings& settings) {
  const auto text = [](double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", value);
    return std::string(buffer);
  };
  if (!(std::isfinite(settings.tolerance) && settings.tolerance > 0.0)) {
    return "tolerance: expected a positive finite relative tolerance, got " +
           text(settings.tolerance);
  }
  if (!(std::isfinite(settings.absolute_tolerance) && settings.absolute_tolerance >= 0.0)) {
    return "absolute_tolerance: expected a finite absolute tolerance >= 0, got " +
           text(settings.absolute_tolerance);
  }
  return std::nullopt;
}

std::unique_ptr<BodyStepper> make_stepper(IntegratorKind kind, const BodyModel& body,
                                          const BodyState& initial, const StepSettings& settings) {
  using K = IntegratorKind;
  switch (kind) {
    case K::kExplicitEuler:
      return steppers::make_explicit_euler(body);
    case K::kSemiImplicitEuler:
      return steppers::make_semi_implicit_euler(body);
    case K::kLieEuler:
      return steppers::make_lie_euler(body);
    case K::kSeedSemiImplicit:
      return steppers::make_seed_semi_implicit(body);
    case K::kImplicitEuler:
      return steppers::make_implicit_euler(body);
    case K::kRk4:
      return steppers::make_rk4(body);
    case K::kMidpoint:
      return steppers::make_midpoint(body);
    case K::kSplitting:
      return steppers::make_splitting(body, 2);
    case K::kSplitting4:
      return steppers::make_splitting(body, 4);
    case K::kFreeRotor:
      return steppers::make_free_rotor(body);
    case K::kMoserVeselov:
      return steppers::make_moser_veselov(body);
    case K::kDopri:
      if (auto problem = step_settings_problem(settings)) throw InputError(*problem);
      return steppers::make_dopri(body, settings);
    case K::kExact:  // refuses bodies without a closed form (exact_stepper.cpp)
      return steppers::make_exact(body, initial);
  }
  throw std::logic_error("make_stepper: unknown kind");
}

}  // namespace tumble::engine
