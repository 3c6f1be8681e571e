#include <impactlab/oscillators/model_file/model_kernels.hpp>

#include <array>

namespace impactlab {

using Kind = KernelOperation::Kind;

SlotProgram::SlotProgram(const KernelCode& code) {
  std::vector<std::uint32_t> slot_of(code.operations.size());
  for (std::size_t i = 0; i < code.operations.size(); ++i) {
    const KernelOperation& operation = code.operations[i];
    const auto next_slot = [&] { return static_cast<std::uint32_t>(steps_.size()); };
    if (operation.operands.empty()) {
      steps_.push_back({operation.kind, operation.index, 0, operation.value});
    } else if (operation.kind == Kind::add || operation.kind == Kind::multiply) {
      std::uint32_t partial = slot_of[operation.operands[0]];
      for (std::size_t k = 1; k < operation.operands.size(); ++k) {
        steps_.push_back({operation.kind, partial, slot_of[operation.operands[k]], 0.0});
        partial = next_slot() - 1;
      }
      slot_of[i] = partial;
      continue;
    } else {
      const std::uint32_t b = operation.operands.size() > 1 ? slot_of[operation.operands[1]] : 0;
      steps_.push_back({operation.kind, slot_of[operation.operands[0]], b, 0.0});
    }
    slot_of[i] = next_slot() - 1;
  }
  for (const std::uint32_t output : code.outputs) outputs_.push_back(slot_of[output]);
}

void SlotProgram::run(const double* x, double t, const double* p, double* out) const {
  constexpr std::size_t slots_on_stack = 512;
  std::array<double, slots_on_stack> on_stack;
  std::vector<double> on_heap;
  double* slot = on_stack.data();
  if (steps_.size() > slots_on_stack) {
    on_heap.resize(steps_.size());
    slot = on_heap.data();
  }
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    const Step& step = steps_[i];
    double& value = slot[i];
    switch (step.kind) {
      case Kind::constant: value = step.value; break;
      case Kind::state: value = x[step.a]; break;
      case Kind::parameter: value = p[step.a]; break;
      case Kind::time: value = t; break;
      default: value = evaluate_operation(step.kind, slot[step.a], slot[step.b]); break;
    }
  }
  for (std::size_t i = 0; i < outputs_.size(); ++i) out[i] = slot[outputs_[i]];
}

}  // namespace impactlab
