#pragma once
// The integrators of the shooting reference (rod_integrator.hpp), in a header of its own so that code
// can name them without including rod_ode.hpp (whose RodState clashes with collocation_rod.hpp's).
namespace pcr {

enum class IntegratorMethod { RK4, DormandPrince };
const char* to_string(IntegratorMethod method);

}  // namespace pcr
