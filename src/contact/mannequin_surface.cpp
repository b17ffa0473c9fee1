#include "contact/mannequin_surface.hpp"

#include "mesh/mannequin.hpp"

namespace sartor::contact {

namespace {

class SmoothMannequin : public Shape {
public:
  SurfaceQuery query(const Eigen::Vector3d& p) const override {
    const MannequinFieldValue field = mannequin_field_derivatives(p);
    SurfaceQuery result;
    result.distance = field.value;
    result.normal = field.gradient;
    result.hessian = field.hessian;
    const double slope = field.gradient.squaredNorm();
    result.closest = slope > 0.0 ? Eigen::Vector3d(p - field.value / slope * field.gradient) : p;
    return result;
  }

  std::string describe() const override { return "mannequin (smooth implicit surface)"; }

  // The ellipsoids' first-order distances steepen away from their surfaces:
  // the flat hand's slope reaches 6.7 a few metres from the body (sampled in
  // a 6 m box; far out the gradient is homogeneous of degree 0, so it grows
  // no further).
  double slope_bound() const override { return 8.0; }
};

} // namespace

std::unique_ptr<Shape> make_smooth_mannequin_shape() {
  return std::make_unique<SmoothMannequin>();
}

} // namespace sartor::contact
