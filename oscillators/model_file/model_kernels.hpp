// The functions a model is made of, callable without GiNaC: a compiled C
// function from the model's shared object, or (the slow path, when no compiler
// or cache is usable) a stack program interpreted over the same expressions.
// Both have the signature  out = f(x, t, p):  x the state (N), t the time,
// p the parameters in the model's order, out the kernel's outputs.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace impactlab {

using KernelFunction = void (*)(const double* x, double t, const double* p, double* out);

// One instruction of the interpreted evaluator (a stack machine).
struct StackInstruction {
  enum class Op : std::uint8_t {
    constant, state, time, parameter,  // push a value
    add, multiply, power, square,      // binary (square is unary)
    sin, cos, tan, asin, acos, atan, atan2, sinh, cosh, tanh, exp, log, abs,
    store,                             // pop into out[index]
  };
  Op op = Op::constant;
  std::uint32_t index = 0;  // state, parameter or output index
  double value = 0.0;       // constant
};

// The slow path: every output of one kernel as postfix code. Thread-safe (the
// stack lives on the caller's stack); about an order of magnitude slower than
// the compiled code (docs/extending.md has the measurement).
class StackProgram {
 public:
  static constexpr std::size_t max_depth = 64;

  explicit StackProgram(std::vector<StackInstruction> code) : code_(std::move(code)) {}

  void run(const double* x, double t, const double* p, double* out) const {
    double stack[max_depth];
    std::size_t top = 0;  // number of values on the stack
    using Op = StackInstruction::Op;
    for (const StackInstruction& in : code_) {
      switch (in.op) {
        case Op::constant: stack[top++] = in.value; break;
        case Op::state: stack[top++] = x[in.index]; break;
        case Op::time: stack[top++] = t; break;
        case Op::parameter: stack[top++] = p[in.index]; break;
        case Op::add: --top; stack[top - 1] += stack[top]; break;
        case Op::multiply: --top; stack[top - 1] *= stack[top]; break;
        case Op::power: --top; stack[top - 1] = std::pow(stack[top - 1], stack[top]); break;
        case Op::square: stack[top - 1] *= stack[top - 1]; break;
        case Op::atan2: --top; stack[top - 1] = std::atan2(stack[top - 1], stack[top]); break;
        case Op::sin: stack[top - 1] = std::sin(stack[top - 1]); break;
        case Op::cos: stack[top - 1] = std::cos(stack[top - 1]); break;
        case Op::tan: stack[top - 1] = std::tan(stack[top - 1]); break;
        case Op::asin: stack[top - 1] = std::asin(stack[top - 1]); break;
        case Op::acos: stack[top - 1] = std::acos(stack[top - 1]); break;
        case Op::atan: stack[top - 1] = std::atan(stack[top - 1]); break;
        case Op::sinh: stack[top - 1] = std::sinh(stack[top - 1]); break;
        case Op::cosh: stack[top - 1] = std::cosh(stack[top - 1]); break;
        case Op::tanh: stack[top - 1] = std::tanh(stack[top - 1]); break;
        case Op::exp: stack[top - 1] = std::exp(stack[top - 1]); break;
        case Op::log: stack[top - 1] = std::log(stack[top - 1]); break;
        case Op::abs: stack[top - 1] = std::fabs(stack[top - 1]); break;
        case Op::store: out[in.index] = stack[--top]; break;
      }
    }
  }

 private:
  std::vector<StackInstruction> code_;
};

// A kernel: the compiled function where there is one, else the program.
struct Kernel {
  KernelFunction compiled = nullptr;
  const StackProgram* interpreted = nullptr;

  void operator()(const double* x, double t, const double* p, double* out) const {
    if (compiled) {
      compiled(x, t, p, out);
      return;
    }
    interpreted->run(x, t, p, out);
  }
  [[nodiscard]] bool present() const { return compiled || interpreted; }
};

}  // namespace impactlab
