// The definition of SeriesProgram::run (series_program.hpp), included only by
// series_program_series.cpp and series_program_lanes.cpp, which compile it
// for the listed number types.
#pragma once

#include <cmath>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <type_traits>

#include <impactlab/oscillators/model_file/series_program.hpp>

namespace impactlab {

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
  using std::fabs;
  using std::sin;
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
      case Operation::sin: std::construct_at(value, sin(slot[step.a])); break;
      case Operation::cos: std::construct_at(value, cos(slot[step.a])); break;
      case Operation::abs: std::construct_at(value, fabs(slot[step.a])); break;
      default: std::construct_at(value, less_common_function(step, slot[step.a])); break;
    }
  }
  for (std::size_t i = 0; i < outputs_.size(); ++i) out[i] = slot[outputs_[i]];
}

template <class Number>
Number SeriesProgram::less_common_function(const Step& step, const Number& a) {
  using std::cos;
  using std::exp;
  using std::log;
  using std::pow;
  using std::sin;
  using std::sqrt;
  switch (step.operation) {
    case Operation::real_power: return pow(a, step.value);
    case Operation::tan: return sin(a) / cos(a);
    case Operation::exp: return exp(a);
    case Operation::log: return log(a);
    case Operation::sqrt: return sqrt(a);
    case Operation::sinh: return (exp(a) - exp(-a)) * 0.5;
    case Operation::cosh: return (exp(a) + exp(-a)) * 0.5;
    case Operation::tanh: return 1.0 - 2.0 / (exp(2.0 * a) + 1.0);  // ±1 without overflow far out
    default: throw std::logic_error("SeriesProgram: an operation without its case");
  }
}

}  // namespace impactlab
