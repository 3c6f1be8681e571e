// The C source of a model's kernels (kernel_code.hpp): one function
// `impactlab_kernel_<k>(x, t, p, out)` per kernel, each operation that is not
// a leaf a `const double` of its own, in the kernels' canonical order. The
// same kernels give the same text, so the text is what the compile cache
// (compile_cache.hpp) is keyed on.
#pragma once

#include <string>
#include <vector>

#include <impactlab/oscillators/model_file/kernel_code.hpp>

namespace impactlab {

std::string model_c_source(const std::vector<KernelCode>& kernels);

}  // namespace impactlab
