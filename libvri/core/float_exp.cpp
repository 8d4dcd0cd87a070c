#include "libvri/core/float_exp.h"

#include "libvri/core/exp_kernel.h"
#include "libvri/core/scalar_exp_ops.h"

namespace vri {

float expFloat(float x) { return exp_kernel::exp(ScalarExpOps{}, x); }
float expm1Float(float x) { return exp_kernel::expm1(ScalarExpOps{}, x); }

}  // namespace vri
