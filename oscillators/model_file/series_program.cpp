#include <impactlab/oscillators/model_file/series_program.hpp>

#include <cmath>

#include <fmt/format.h>

namespace impactlab {

namespace {

using Kind = KernelOperation::Kind;

// which operations the first `output_count` outputs need
std::vector<bool> needed_operations(const KernelCode& code, std::size_t output_count) {
  std::vector<bool> needed(code.operations.size(), false);
  for (std::size_t i = 0; i < output_count && i < code.outputs.size(); ++i)
    needed[code.outputs[i]] = true;
  // each operation comes after its operands: one backward pass marks them all
  for (std::size_t i = code.operations.size(); i-- > 0;)
    if (needed[i])
      for (const std::uint32_t operand : code.operations[i].operands) needed[operand] = true;
  return needed;
}

// the exponent of a power, where it is a constant
bool constant_exponent(const KernelCode& code, const KernelOperation& power, double& exponent) {
  if (power.operands.size() != 2) return false;
  const KernelOperation& operand = code.operations[power.operands[1]];
  if (operand.kind != Kind::constant) return false;
  exponent = operand.value;
  return true;
}

// whether a constant exponent is an integer computed as products
bool small_integer(double exponent) {
  return exponent == std::round(exponent) && std::fabs(exponent) <= SeriesProgram::max_exponent;
}

// the steps an operation takes: a sum or product of n operands n − 1
std::size_t step_count(const KernelOperation& operation) {
  if ((operation.kind == Kind::add || operation.kind == Kind::multiply) &&
      operation.operands.size() > 1)
    return operation.operands.size() - 1;
  return 1;
}

}  // namespace

std::string series_refusal(const KernelCode& code, std::size_t output_count) {
  const std::vector<bool> needed = needed_operations(code, output_count);
  std::size_t steps = 0;
  for (std::size_t i = 0; i < code.operations.size(); ++i) {
    if (!needed[i]) continue;
    const KernelOperation& operation = code.operations[i];
    steps += step_count(operation);
    switch (operation.kind) {
      case Kind::constant:
      case Kind::state:
      case Kind::parameter:
      case Kind::time:
      case Kind::add:
      case Kind::multiply:
      case Kind::square:
      case Kind::reciprocal:
      case Kind::sin:
      case Kind::cos:
      case Kind::tan:
      case Kind::exp:
      case Kind::log:
      case Kind::square_root:
      case Kind::sinh:
      case Kind::cosh:
      case Kind::tanh:
      case Kind::abs: break;
      case Kind::power: {
        double exponent = 0.0;
        if (!constant_exponent(code, operation, exponent))
          return "it raises to a power whose exponent is not a constant";
        break;
      }
      case Kind::atan2: return "it uses atan2";
      default: return fmt::format("it uses {}", c_function_name(operation.kind));
    }
  }
  if (steps > SeriesProgram::max_steps)
    return fmt::format("it takes {} operations, more than the {} a series evaluation holds", steps,
                       SeriesProgram::max_steps);
  return {};
}

SeriesProgram::SeriesProgram(const KernelCode& code, std::size_t output_count) {
  if (const std::string why = series_refusal(code, output_count); !why.empty())
    throw std::invalid_argument("SeriesProgram: " + why);
  const std::vector<bool> needed = needed_operations(code, output_count);
  std::vector<std::uint32_t> slot_of(code.operations.size());
  const auto last_slot = [&] { return static_cast<std::uint32_t>(steps_.size() - 1); };
  for (std::size_t i = 0; i < code.operations.size(); ++i) {
    if (!needed[i]) continue;
    const KernelOperation& operation = code.operations[i];
    const auto operand = [&](std::size_t k) { return slot_of[operation.operands[k]]; };
    switch (operation.kind) {
      case Kind::constant: steps_.push_back({Operation::constant, 0, 0, operation.value}); break;
      case Kind::state: steps_.push_back({Operation::state, operation.index}); break;
      case Kind::parameter: steps_.push_back({Operation::parameter, operation.index}); break;
      case Kind::time: steps_.push_back({Operation::time}); break;
      case Kind::add:
      case Kind::multiply: {
        const Operation folded =
            operation.kind == Kind::add ? Operation::add : Operation::multiply;
        std::uint32_t partial = operand(0);
        for (std::size_t k = 1; k < operation.operands.size(); ++k) {
          steps_.push_back({folded, partial, operand(k)});
          partial = last_slot();
        }
        slot_of[i] = partial;
        continue;
      }
      case Kind::square: steps_.push_back({Operation::multiply, operand(0), operand(0)}); break;
      case Kind::reciprocal: steps_.push_back({Operation::reciprocal, operand(0)}); break;
      case Kind::power: {
        double exponent = 0.0;
        constant_exponent(code, operation, exponent);
        if (small_integer(exponent))
          steps_.push_back({Operation::integer_power, operand(0), 0, 0.0, static_cast<int>(exponent)});
        else
          steps_.push_back({Operation::real_power, operand(0), 0, exponent});
        break;
      }
      case Kind::sin: steps_.push_back({Operation::sin, operand(0)}); break;
      case Kind::cos: steps_.push_back({Operation::cos, operand(0)}); break;
      case Kind::tan: steps_.push_back({Operation::tan, operand(0)}); break;
      case Kind::exp: steps_.push_back({Operation::exp, operand(0)}); break;
      case Kind::log: steps_.push_back({Operation::log, operand(0)}); break;
      case Kind::square_root: steps_.push_back({Operation::sqrt, operand(0)}); break;
      case Kind::sinh: steps_.push_back({Operation::sinh, operand(0)}); break;
      case Kind::cosh: steps_.push_back({Operation::cosh, operand(0)}); break;
      case Kind::tanh: steps_.push_back({Operation::tanh, operand(0)}); break;
      case Kind::abs: steps_.push_back({Operation::abs, operand(0)}); break;
      default: break;  // refused above
    }
    slot_of[i] = last_slot();
  }
  for (std::size_t i = 0; i < output_count && i < code.outputs.size(); ++i)
    outputs_.push_back(slot_of[code.outputs[i]]);
}

}  // namespace impactlab
