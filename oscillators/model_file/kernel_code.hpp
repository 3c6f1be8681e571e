// A model's kernels as straight-line code in a canonical order of its own:
// every distinct subexpression of a kernel is one operation, computed once
// (a chain of definitions that names the one before several times stays
// linear), and the operands of a sum or a product are in an order given by
// their structure alone. The same model text therefore gives the same
// operations, the same C source (model_c_source.hpp) and the same
// interpreted program (model_kernels.hpp) in every process, whereas GiNaC
// orders the operands of a sum or product by hash values that depend on
// memory addresses, so that its own printer's output changes from one process
// to the next.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace GiNaC {
class ex;
}

namespace impactlab {

// One value of a kernel, computed from earlier ones.
struct KernelOperation {
  enum class Kind : std::uint8_t {
    constant, state, parameter, time,          // leaves
    add, multiply,                             // n-ary, folded left to right
    power, atan2,                              // binary
    square, reciprocal, square_root,           // the powers 2, −1 and 1/2
    sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, exp, log, abs,
  };
  Kind kind = Kind::constant;
  std::uint32_t index = 0;               // the state's or parameter's index
  double value = 0.0;                    // the constant
  std::vector<std::uint32_t> operands;   // earlier operations, in order
};

// The name of a unary function kind as C's math.h spells it (fabs for abs).
std::string_view c_function_name(KernelOperation::Kind kind);

// The value of an operation that is not a leaf from its operands' values
// (`b` unused by the unary ones; a sum or product of two). The interpreted
// evaluator runs this; the code generator folds with it an operation whose
// operands are all constants, so that no constant is computed by the C
// compiler (which folds tanh(1/6) correctly rounded, where the C library at
// run time may differ in the last bit).
inline double evaluate_operation(KernelOperation::Kind kind, double a, double b) {
  using Kind = KernelOperation::Kind;
  switch (kind) {
    case Kind::add: return a + b;
    case Kind::multiply: return a * b;
    case Kind::power: return std::pow(a, b);
    case Kind::atan2: return std::atan2(a, b);
    case Kind::square: return a * a;
    case Kind::reciprocal: return 1.0 / a;
    case Kind::square_root: return std::sqrt(a);
    case Kind::sin: return std::sin(a);
    case Kind::cos: return std::cos(a);
    case Kind::tan: return std::tan(a);
    case Kind::asin: return std::asin(a);
    case Kind::acos: return std::acos(a);
    case Kind::atan: return std::atan(a);
    case Kind::sinh: return std::sinh(a);
    case Kind::cosh: return std::cosh(a);
    case Kind::tanh: return std::tanh(a);
    case Kind::exp: return std::exp(a);
    case Kind::log: return std::log(a);
    case Kind::abs: return std::fabs(a);
    default: return a;  // the leaves have no operands
  }
}

struct KernelCode {
  std::vector<KernelOperation> operations;  // each after its operands
  std::vector<std::uint32_t> outputs;       // the operation of out[i]
};

// The code of one kernel from its outputs, expressions in the symbols x[i],
// p[j] and t with real numbers that are finite doubles. Throws
// std::length_error when the kernel would take more than `max_operations`
// operations (a leaf counts one, a sum or product of n operands n − 1).
KernelCode kernel_code(const std::vector<GiNaC::ex>& outputs, std::size_t max_operations);

}  // namespace impactlab
