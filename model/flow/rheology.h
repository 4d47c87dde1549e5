// SPDX-License-Identifier: MIT
// The paste's viscosity law: the one interface the flow solver asks for a viscosity through.
//
// The solver evaluates the law once per cell and step at the cell's strain-rate magnitude
// gamma_dot = sqrt(2 D:D) (1/s, D the strain-rate tensor, from the velocity at the start of the step), so a
// shear-thinning law (regularised Bingham, Herschel-Bulkley: part 2) is lagged by one step (Picard) and the
// implicit viscous solve stays linear. The air is Newtonian. The mixture viscosity of a cell with paste
// fraction alpha is alpha eta_paste + (1 - alpha) eta_air; the shear stresses between cells use the harmonic
// mean of the cells around an edge (model/flow/viscous.cpp), so a thin air layer lubricates as it should.
#pragma once

#include <memory>
#include <string>

namespace pastemix::flow {

class Rheology {
 public:
  virtual ~Rheology() = default;
  // Apparent viscosity (Pa s, > 0) at the strain-rate magnitude gamma_dot (1/s, >= 0).
  virtual double viscosity(double gamma_dot) const = 0;
  // False for a Newtonian law: the solver then skips computing gamma_dot.
  virtual bool shear_dependent() const = 0;
  virtual std::string describe() const = 0;
};

class Newtonian final : public Rheology {
 public:
  explicit Newtonian(double eta_Pa_s) : eta_(eta_Pa_s) {}
  double viscosity(double) const override { return eta_; }
  bool shear_dependent() const override { return false; }
  std::string describe() const override;

 private:
  double eta_;  // Pa s
};

// The two phases. "Paste" is the phase tracked by the volume fraction alpha (water in the dam break).
struct Phases {
  double rho_paste = 1850.0;  // kg/m3
  double rho_air = 1.2;       // kg/m3
  double eta_air = 1.8e-5;    // Pa s
  std::shared_ptr<const Rheology> paste = std::make_shared<Newtonian>(1.0);
  double density(double alpha) const { return rho_air + (rho_paste - rho_air) * alpha; }
};

}  // namespace pastemix::flow
