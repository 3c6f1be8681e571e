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
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
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
  void run(const Number* x, const Number& t, const double* p, Number* out) const;

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

  std::vector<Step> steps_;
  std::vector<std::uint32_t> outputs_;  // the slot of out[i]
};

// Empty where every operation that the first `output_count` outputs of `code`
// need has a series and they fit in SeriesProgram::max_steps; otherwise why
// not, as a phrase ("it uses exp").
std::string series_refusal(const KernelCode& code, std::size_t output_count);

template <class Number>
Number SeriesProgram::integer_power(const Number& base, int exponent) {
  if (exponent == 0) return Number(1.0);
  const int count = exponent < 0 ? -exponent : exponent;
  Number power = base;
  for (int k = 1; k < count; ++k) power = power * base;
  if (exponent < 0) return Number(1.0) / power;
  return power;
}

template <class Number>
void SeriesProgram::run(const Number* x, const Number& t, const double* p, Number* out) const {
  static_assert(std::is_trivially_destructible_v<Number>,
                "the slots are constructed in place and never destroyed");
  if (empty()) throw std::logic_error("SeriesProgram: run on a model without series");
  // uninitialised storage: each slot is constructed by its step
  alignas(Number) std::byte storage[max_steps * sizeof(Number)];
  Number* const slot = reinterpret_cast<Number*>(storage);
  using std::cos;
  using std::exp;
  using std::fabs;
  using std::log;
  using std::pow;
  using std::sin;
  using std::sqrt;
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    const Step& step = steps_[i];
    Number* const value = slot + i;
    switch (step.operation) {
      case Operation::constant: std::construct_at(value, step.value); break;
      case Operation::state: std::construct_at(value, x[step.a]); break;
      case Operation::parameter: std::construct_at(value, p[step.a]); break;
      case Operation::time: std::construct_at(value, t); break;
      case Operation::add: std::construct_at(value, slot[step.a] + slot[step.b]); break;
      case Operation::multiply: std::construct_at(value, slot[step.a] * slot[step.b]); break;
      case Operation::reciprocal: std::construct_at(value, Number(1.0) / slot[step.a]); break;
      case Operation::integer_power:
        std::construct_at(value, integer_power(slot[step.a], step.exponent));
        break;
      case Operation::real_power: std::construct_at(value, pow(slot[step.a], step.value)); break;
      case Operation::sin: std::construct_at(value, sin(slot[step.a])); break;
      case Operation::cos: std::construct_at(value, cos(slot[step.a])); break;
      case Operation::tan: std::construct_at(value, sin(slot[step.a]) / cos(slot[step.a])); break;
      case Operation::exp: std::construct_at(value, exp(slot[step.a])); break;
      case Operation::log: std::construct_at(value, log(slot[step.a])); break;
      case Operation::sqrt: std::construct_at(value, sqrt(slot[step.a])); break;
      case Operation::sinh:
        std::construct_at(value, (exp(slot[step.a]) - exp(-slot[step.a])) * 0.5);
        break;
      case Operation::cosh:
        std::construct_at(value, (exp(slot[step.a]) + exp(-slot[step.a])) * 0.5);
        break;
      case Operation::tanh:  // 1 − 2 / (e^{2a} + 1): ±1 without overflow far out
        std::construct_at(value, 1.0 - 2.0 / (exp(2.0 * slot[step.a]) + 1.0));
        break;
      case Operation::abs: std::construct_at(value, fabs(slot[step.a])); break;
    }
  }
  for (std::size_t i = 0; i < outputs_.size(); ++i) out[i] = slot[outputs_[i]];
}

}  // namespace impactlab
