// A model's kernel run over a number type other than double: the Taylor
// stepper's series (integrate/taylor_series.hpp), the batch's tapes
// (integrate/series_tape.hpp), and the dual numbers of the variational
// equations over either. The kernel's operations (kernel_code.hpp) run one
// after the other as the interpreted evaluator runs them (model_kernels.hpp),
// sums and products folded left to right, each into a slot that holds a
// number of that type; the unqualified calls find the type's own sin, cos
// and fabs.
//
// Only the operations whose series that arithmetic has: sums, products,
// quotients, powers with a constant exponent (an integer of at most
// max_exponent in size as products, any other by the power's own
// recurrence), sin, cos, tan, exp, log, √, sinh, cosh, tanh and |·|.
// series_refusal says which other operation a kernel holds (the inverse
// trigonometric functions, a power whose exponent is not a constant); a
// model with one offers no Taylor stepper.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <impactlab/oscillators/model_file/kernel_code.hpp>

namespace impactlab {

class SeriesProgram {
 public:
  // the most steps (leaves and operations) a program may take: its slots
  // are on the caller's stack, sized once, so that nothing is allocated
  static constexpr std::size_t max_steps = 512;
  // the largest |n| of a power x^n computed as products
  static constexpr int max_exponent = 16;

  SeriesProgram() = default;
  // The steps of the first `output_count` outputs of `code` (those they
  // need only). std::invalid_argument where series_refusal(code) is not
  // empty.
  SeriesProgram(const KernelCode& code, std::size_t output_count);

  [[nodiscard]] bool empty() const { return outputs_.empty(); }

  // out[i] = output i at the state x (N numbers), the time t and the
  // parameters p (the model's order). std::logic_error for an empty program.
  template <class Number>
  [[gnu::flatten]] void run(const Number* x, const Number& t, const double* p, Number* out) const;

 private:
  enum class Operation : std::uint8_t {
    constant, state, parameter, time, add, multiply, reciprocal,
    integer_power, real_power, sin, cos, tan, exp, log, sqrt, sinh, cosh, tanh, abs
  };
  struct Step {
    Operation operation = Operation::constant;
    std::uint32_t a = 0, b = 0;  // operand slots, or the state's or parameter's index
    double value = 0.0;          // the constant, or real_power's exponent
    int exponent = 0;            // integer_power's
  };

  template <class Number>
  static Number integer_power(const Number& base, int exponent);
  // The functions other than sin, cos and |·|, called from run's loop: the
  // loop has every other operation inlined (flattened, it is the Taylor
  // stepper's hot path), and these, inlined too, made a dual number's loop
  // ten times as long to compile (15 to 60 s per type).
  template <class Number>
  [[gnu::noinline]] static Number less_common_function(const Step& step, const Number& a);

  std::vector<Step> steps_;
  std::vector<std::uint32_t> outputs_;  // the slot of out[i]
};

// Empty where every operation that the first `output_count` outputs of `code`
// need has a series and they fit in SeriesProgram::max_steps; otherwise why
// not, as a phrase ("it uses exp").
std::string series_refusal(const KernelCode& code, std::size_t output_count);

// run is defined in series_program_run.hpp and compiled once per number type
// listed here, in series_program_series.cpp (doubles, the Taylor stepper's
// series and their dual numbers) and series_program_lanes.cpp (the batch's
// tapes and their dual numbers): its switch over every operation, inlined
// into each system's flows, made those units several times the cost of any
// other. A type not listed fails to link, naming it.
template <class Real>
class TaylorVariable;
class TapeVariable;
template <class Number, std::size_t Directions>
class Dual;

#define IMPACTLAB_SERIES_PROGRAM_NUMBER_TYPES(X) \
  X(double)                                     \
  X(TaylorVariable<double>)                     \
  X(Dual<TaylorVariable<double>, 2>)            \
  X(Dual<TaylorVariable<double>, 4>)

#define IMPACTLAB_SERIES_PROGRAM_LANE_TYPES(X) \
  X(TapeVariable)                              \
  X(Dual<TapeVariable, 2>)                     \
  X(Dual<TapeVariable, 4>)

// the explicit instantiation of run for one number type
#define IMPACTLAB_SERIES_PROGRAM_RUN(...)                                               \
  template void SeriesProgram::run<__VA_ARGS__>(const __VA_ARGS__*, const __VA_ARGS__&, \
                                                const double*, __VA_ARGS__*) const;

}  // namespace impactlab
