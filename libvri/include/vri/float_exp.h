#pragma once
// exp and expm1 of the float fixed-step path, shared bit for bit with the packet engine's vector
// versions (libvri/src/exp_kernel.h): within 1 ulp of the correctly rounded value for normal results
// (tests/unit/float_exp_test.cpp measures it), 0 below -103.97, +inf above 88.73, NaN for NaN.
// Double precision keeps std::exp and std::expm1.
namespace vri {

float expFloat(float x);
float expm1Float(float x);

}  // namespace vri
