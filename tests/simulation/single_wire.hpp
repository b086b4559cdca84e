// The single wire of the statics tests (test_conditions.cpp, test_wind.cpp)
// and its independent reference:
//  - single_wire_mesh(L0): a 60 m contact wire (EN 50318's: 1.35 kg/m, EA
//    1.44e7 N) of unstressed length L0, 120 elements, EI 1 N m^2 (bending
//    ~1e-8 of the tension's stiffness over the span), built for ~20 kN;
//  - GreenCatenary: the elastic catenary with the elements' Green strain, a
//    wire of unstressed length L0 under a load w per unstressed length, with
//    horizontal force H between level supports; unstressed coordinate s,
//    axial rigidity EA (T = EA lambda (lambda^2 - 1) / 2), integrated
//    numerically.
#pragma once

#include <cmath>
#include <functional>

#include "../assembly/catenary_fixtures.hpp"

namespace pcsim::test {

constexpr double kWireSpan = 60, kWireMass = 1.35, kWireEA = 1.44e7;  // m, kg/m, N
constexpr int kWireElements = 120;

inline catenary::CatenaryMesh single_wire_mesh(double L0) {
  auto mesh =
      fixtures::single_wire(kWireSpan, kWireElements, kWireMass, kWireEA, 1.0, 20000, 0.3, 1.0);
  double ref_total = 0;
  for (const auto& e : mesh.cables) ref_total += e.ref_length;
  for (auto& e : mesh.cables) e.unstressed_length = e.ref_length * L0 / ref_total;
  return mesh;
}

struct GreenCatenary {
  double H, w, L0;
  double EA = 1.44e7;               // [N]
  double stretch(double T) const {  // lambda from T = EA lambda (lambda^2 - 1) / 2
    double lambda = 1 + T / EA;
    for (int it = 0; it < 30; ++it)
      lambda -=
          (0.5 * EA * lambda * (lambda * lambda - 1) - T) / (0.5 * EA * (3 * lambda * lambda - 1));
    return lambda;
  }
  // int_0^upto f(s) ds by Simpson's rule on 4000 intervals.
  double integral(double upto, const std::function<double(double)>& f) const {
    const int n = 4000;
    const double h = upto / n;
    double sum = f(0) + f(upto);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * f(i * h);
    return sum * h / 3;
  }
  double span() const {  // x(L0) = int lambda H / T ds
    return integral(L0, [&](double s) {
      const double T = std::hypot(H, 0.5 * w * L0 - w * s);
      return stretch(T) * H / T;
    });
  }
  double sag() const {  // -z(L0 / 2) = int lambda (V - w s) / T ds
    return integral(0.5 * L0, [&](double s) {
      const double T = std::hypot(H, 0.5 * w * L0 - w * s);
      return stretch(T) * (0.5 * w * L0 - w * s) / T;
    });
  }
  void fit_span(double span) {  // H such that x(L0) = span (secant)
    double h0 = H, h1 = 1.01 * H, f0 = this->span() - span;
    for (int it = 0; it < 40 && std::abs(f0) > 1e-13 * span; ++it) {
      H = h1;
      const double f1 = this->span() - span;
      h1 = h1 - f1 * (h1 - h0) / (f1 - f0);
      h0 = H, f0 = f1;
    }
  }
};

}  // namespace pcsim::test
