#pragma once
// The integrators of the shooting reference (rod_integrator.hpp), in a header of its own so that code
// can name them without including rod_ode.hpp.
namespace pcr {

enum class IntegratorMethod { RK4, DormandPrince };
const char* to_string(IntegratorMethod method);

}  // namespace pcr
