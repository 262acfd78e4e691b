// The `exact` integrator: a closed-form solution evaluated at each output time from the initial
// state (not step by step), so its error does not grow with the number of steps.
// - torque-free bodies: TorqueFreeMotion (engine/PHYSICS.md §4), L held at its initial value,
//   and for free bodies the centre of mass on its parabola x0 + v0 t + g t^2 / 2;
// - Lagrange tops (pivoted symmetric bodies under gravity): LagrangeTop (§4b), which gives
//   both the orientation and the turning world L.
// Any other forced body has no closed form here and is refused at creation.
#include <optional>
#include <variant>

#include "base/errors.hpp"
#include "engine/exact/lagrange_top.hpp"
#include "engine/exact/torque_free_exact.hpp"
#include "steppers.hpp"

namespace tumble::engine::steppers {
namespace {

class TorqueFreeExact final : public BodyStepper {
 public:
  TorqueFreeExact(const BodyModel& body, const BodyState& initial)
      : body_(body),
        initial_(initial),
        motion_(body.moments, initial.orientation,
                (initial.orientation.conjugate() * initial.angular_momentum)
                    .cwiseQuotient(body.moments)) {
    for (const ForceTerm& term : body.forces) {
      if (const auto* g = std::get_if<Gravity>(&term)) gravity_ += g->acceleration;
    }
  }
  void step(BodyState& s, double t, double h) override {
    const double time = t + h;
    s.orientation = motion_.at(time).orientation;
    s.angular_momentum = initial_.angular_momentum;
    if (!body_.pivoted) {
      s.position = initial_.position + time * initial_.velocity + 0.5 * time * time * gravity_;
      s.velocity = initial_.velocity + time * gravity_;
    }
  }

 private:
  const BodyModel& body_;
  BodyState initial_;
  TorqueFreeMotion motion_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
};

class LagrangeTopExact final : public BodyStepper {
 public:
  LagrangeTopExact(const BodyModel& body, const BodyState& initial) : top_(body, initial) {}
  void step(BodyState& s, double t, double h) override {
    const BodyState next = top_.at(t + h);
    s.orientation = next.orientation;
    s.angular_momentum = next.angular_momentum;
  }

 private:
  LagrangeTop top_;
};

}  // namespace

std::unique_ptr<BodyStepper> make_exact(const BodyModel& body, const BodyState& initial) {
  if (body.torque_free()) return std::make_unique<TorqueFreeExact>(body, initial);
  if (const std::optional<std::string> problem = lagrange_top_problem(body)) {
    throw InputError("body '" + body.name +
                     "': the exact integrator needs a torque-free body or a heavy symmetric top "
                     "(pivoted, gravity only, two equal moments, centre of mass on the third "
                     "axis), and " +
                     *problem + "; choose another integrator");
  }
  return std::make_unique<LagrangeTopExact>(body, initial);
}

}  // namespace tumble::engine::steppers
