// The functions a model is made of, callable without GiNaC: a compiled C
// function from the model's shared object, or (the slow path, when no compiler
// or cache is usable) the same operations run by an interpreter.
// Both have the signature  out = f(x, t, p):  x the state (N), t the time,
// p the parameters in the model's order, out the kernel's outputs.
#pragma once

#include <cstdint>
#include <vector>

#include <impactlab/oscillators/model_file/kernel_code.hpp>

namespace impactlab {

using KernelFunction = void (*)(const double* x, double t, const double* p, double* out);

// The slow path: a kernel's operations (kernel_code.hpp) run one after the
// other, each into its own slot, sums and products folded left to right as
// the C code does, so that it gives the compiled code's numbers. Thread-safe
// (the slots live on the caller's stack, or for a large kernel in a buffer
// of the call); about an order of magnitude slower than the compiled code
// (docs/extending.md has the measurement).
class SlotProgram {
 public:
  explicit SlotProgram(const KernelCode& code);
  void run(const double* x, double t, const double* p, double* out) const;

 private:
  // One step: a leaf (its index or value) or an operation of one or two
  // earlier slots; a sum or product of n operands is n − 1 steps.
  struct Step {
    KernelOperation::Kind kind = KernelOperation::Kind::constant;
    std::uint32_t a = 0, b = 0;  // operand slots, or the state's or parameter's index
    double value = 0.0;          // the constant
  };
  std::vector<Step> steps_;
  std::vector<std::uint32_t> outputs_;  // the slot of out[i]
};

// A kernel: the compiled function where there is one, else the program.
struct Kernel {
  KernelFunction compiled = nullptr;
  const SlotProgram* interpreted = nullptr;

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
