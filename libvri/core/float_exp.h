#pragma once
// exp and expm1 of the float fixed-step path, shared bit for bit with the packet engine's vector
// versions (exp_kernel.h). Measured against the exact value (tests/unit/float_exp_test.cpp):
// exp within 1.005 ulp where the result is a normal float and within one step 2^-149 where it is
// subnormal, 0 below -103.97, +inf above 88.72; expm1 within 1.7 ulp, exact for |x| < 2^-25 (but
// expm1(-0) = +0); NaN for NaN.
// Double precision keeps std::exp and std::expm1.
namespace vri {

float expFloat(float x);
float expm1Float(float x);

}  // namespace vri
