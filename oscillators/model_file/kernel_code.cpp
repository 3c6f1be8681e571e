#include <impactlab/oscillators/model_file/kernel_code.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <ginac/ginac.h>

namespace impactlab {

namespace {

using Kind = KernelOperation::Kind;

// the largest integer power written as repeated multiplication
constexpr int max_multiplied_power = 8;

// The unary functions GiNaC may hold, by name; atan2 is the one binary
// function, and sqrt and pow are powers.
constexpr std::pair<std::string_view, Kind> unary_functions[] = {
    {"sin", Kind::sin},   {"cos", Kind::cos},   {"tan", Kind::tan},   {"asin", Kind::asin},
    {"acos", Kind::acos}, {"atan", Kind::atan}, {"sinh", Kind::sinh}, {"cosh", Kind::cosh},
    {"tanh", Kind::tanh}, {"exp", Kind::exp},   {"log", Kind::log},   {"abs", Kind::abs}};

// 64 bits of `value` mixed into `hash` (the finaliser of splitmix64).
std::uint64_t mix(std::uint64_t hash, std::uint64_t value) {
  std::uint64_t z = hash ^ (value + 0x9e3779b97f4a7c15ULL + (hash << 6) + (hash >> 2));
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A distinct subexpression. Its hash is a function of its structure alone
// (never of an address), and so is the order of a sum's or product's operands.
struct Node {
  Kind kind = Kind::constant;
  std::uint32_t index = 0;
  double value = 0.0;
  std::vector<std::uint32_t> operands;
  std::uint64_t hash = 0;
};

bool same_leaf(const Node& a, const Node& b) {
  return a.kind == b.kind && a.index == b.index &&
         std::bit_cast<std::uint64_t>(a.value) == std::bit_cast<std::uint64_t>(b.value);
}

// The distinct subexpressions of one kernel, each stored once (hash-consed).
class Interner {
 public:
  explicit Interner(std::size_t max_operations) : max_operations_(max_operations) {}

  std::uint32_t intern(const GiNaC::ex& e) {
    const GiNaC::basic* address = &GiNaC::ex_to<GiNaC::basic>(e);
    if (const auto found = by_address_.find(address); found != by_address_.end())
      return found->second;
    const std::uint32_t id = id_of(e);
    by_address_.emplace(address, id);
    held_.push_back(e);  // so that no address is reused by another subexpression
    return id;
  }

  [[nodiscard]] const Node& node(std::uint32_t id) const { return nodes_[id]; }

  // A total order of distinct nodes given by their structure: the hash,
  // then (for two nodes whose hashes collide) the structure itself.
  [[nodiscard]] bool before(std::uint32_t a, std::uint32_t b) const { return compare(a, b) < 0; }

 private:
  [[nodiscard]] int compare(std::uint32_t a, std::uint32_t b) const {
    if (a == b) return 0;
    const Node& x = nodes_[a];
    const Node& y = nodes_[b];
    if (x.hash != y.hash) return x.hash < y.hash ? -1 : 1;
    if (x.kind != y.kind) return x.kind < y.kind ? -1 : 1;
    if (x.index != y.index) return x.index < y.index ? -1 : 1;
    const auto x_bits = std::bit_cast<std::uint64_t>(x.value);
    const auto y_bits = std::bit_cast<std::uint64_t>(y.value);
    if (x_bits != y_bits) return x_bits < y_bits ? -1 : 1;
    if (x.operands.size() != y.operands.size()) return x.operands.size() < y.operands.size() ? -1 : 1;
    for (std::size_t i = 0; i < x.operands.size(); ++i)
      if (const int c = compare(x.operands[i], y.operands[i]); c != 0) return c;
    return 0;
  }

  Node leaf(Kind kind, std::uint32_t index = 0, double value = 0.0) {
    Node node;
    node.kind = kind;
    node.index = index;
    node.value = value;
    return node;
  }
  // a constant; −0 (a number below the range of a double, negated) is 0,
  // and every NaN the one quiet NaN (a NaN's sign bit depends on how it
  // was computed)
  std::uint32_t constant(double value) {
    if (value == 0.0) value = 0.0;
    if (std::isnan(value)) value = std::numeric_limits<double>::quiet_NaN();
    return store(leaf(Kind::constant, 0, value));
  }
  // the operation, or where every operand is a constant, its value
  std::uint32_t apply(Kind kind, std::vector<std::uint32_t> operands) {
    if (std::all_of(operands.begin(), operands.end(),
                    [this](std::uint32_t id) { return nodes_[id].kind == Kind::constant; })) {
      double value = nodes_[operands[0]].value;
      if (operands.size() == 1) return constant(evaluate_operation(kind, value, 0.0));
      for (std::size_t i = 1; i < operands.size(); ++i)
        value = evaluate_operation(kind, value, nodes_[operands[i]].value);
      return constant(value);
    }
    Node node;
    node.kind = kind;
    node.operands = std::move(operands);
    return store(std::move(node));
  }
  void sort_canonically(std::vector<std::uint32_t>& operands) const {
    std::sort(operands.begin(), operands.end(),
              [this](std::uint32_t a, std::uint32_t b) { return before(a, b); });
  }

  std::uint32_t id_of(const GiNaC::ex& e) {
    if (GiNaC::is_a<GiNaC::numeric>(e)) return constant(GiNaC::ex_to<GiNaC::numeric>(e).to_double());
    if (GiNaC::is_a<GiNaC::constant>(e)) return constant(GiNaC::ex_to<GiNaC::numeric>(e.evalf()).to_double());
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      const std::string name = GiNaC::ex_to<GiNaC::symbol>(e).get_name();
      if (name == "t") return store(leaf(Kind::time));
      const auto index = static_cast<std::uint32_t>(std::stoul(name.substr(2)));
      return store(leaf(name[0] == 'x' ? Kind::state : Kind::parameter, index));
    }
    if (GiNaC::is_a<GiNaC::add>(e)) {
      std::vector<std::uint32_t> terms;
      for (std::size_t i = 0; i < e.nops(); ++i) terms.push_back(intern(e.op(i)));
      return sum(std::move(terms));
    }
    if (GiNaC::is_a<GiNaC::mul>(e)) {
      std::vector<std::uint32_t> factors;
      bool negated = false;
      for (std::size_t i = 0; i < e.nops(); ++i) factors.push_back(sign_normalized(intern(e.op(i)), negated));
      return product(std::move(factors), negated);
    }
    if (GiNaC::is_a<GiNaC::power>(e)) return power_of(e.op(0), e.op(1));
    if (GiNaC::is_a<GiNaC::function>(e)) {
      const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
      if (name == "atan2") return apply(Kind::atan2, {intern(e.op(0)), intern(e.op(1))});
      if (name == "abs" && e.nops() == 1) {
        bool negated = false;  // |−s| = |s|
        return apply(Kind::abs, {sign_normalized(intern(e.op(0)), negated)});
      }
      for (const auto& [known, kind] : unary_functions)
        if (known == name && e.nops() == 1) return apply(kind, {intern(e.op(0))});
      throw std::runtime_error("the model's code has no function " + name);
    }
    throw std::runtime_error("the model's code cannot hold this expression");
  }

  // b^p with the exponents 2, −1, 1/2 and their products written as
  // multiplications, divisions and square roots, and the integers up to
  // ±max_multiplied_power as repeated multiplications; every other one
  // through pow. A sum raised to an integer has its signs normalised (below), the
  // sign of an odd power then standing in front.
  std::uint32_t power_of(const GiNaC::ex& base, const GiNaC::ex& exponent) {
    std::uint32_t b = intern(base);
    if (!GiNaC::is_a<GiNaC::numeric>(exponent)) return apply(Kind::power, {b, intern(exponent)});
    const GiNaC::numeric& p = GiNaC::ex_to<GiNaC::numeric>(exponent);
    bool negated = false;
    if (p.is_integer()) {
      b = sign_normalized(b, negated);
      negated = negated && p.is_odd();
    }
    const std::uint32_t power = [&] {
      if (p.is_integer() && GiNaC::abs(p) >= 3 && GiNaC::abs(p) <= max_multiplied_power) {
        // b·b·…·b: a few multiplications cost a fraction of a call of pow
        const std::uint32_t multiplied =
            apply(Kind::multiply, std::vector<std::uint32_t>(static_cast<std::size_t>(GiNaC::abs(p).to_int()), b));
        return p.is_positive() ? multiplied : apply(Kind::reciprocal, {multiplied});
      }
      if (p == 2) return apply(Kind::square, {b});
      if (p == -1) return apply(Kind::reciprocal, {b});
      if (p == -2) return apply(Kind::reciprocal, {apply(Kind::square, {b})});
      if (p == GiNaC::numeric(1, 2)) return apply(Kind::square_root, {b});
      if (p == GiNaC::numeric(-1, 2)) return apply(Kind::reciprocal, {apply(Kind::square_root, {b})});
      return apply(Kind::power, {b, constant(p.to_double())});
    }();
    return negated ? product({power}, true) : power;
  }

  // --- signs ---
  // GiNaC writes one product as c·(a − b)·z or as (−c)·(b − a)·z, and one
  // power as (a − b)⁻¹ or −(b − a)⁻¹, depending on the order in which it
  // met the factors (an order of addresses). Every sum that is a factor or
  // the base of an integer power is therefore written with the signs that
  // give its leading term (the least hash of a term without its sign) a
  // positive sign, the sign moving to the product.
  // Each way of writing computes the same bits: negation is exact and
  // rounding symmetric.

  // the sign of a term of a sum (that of its constants), and a hash of the
  // term that its sign does not change: x and −x, 2x and −2x hash alike (a
  // product by its factors other than ±1, a constant by its magnitude,
  // combined in no particular order)
  [[nodiscard]] bool negative(std::uint32_t term) const {
    const Node& node = nodes_[term];
    if (node.kind == Kind::constant) return node.value < 0.0;
    bool negative = false;
    if (node.kind == Kind::multiply)
      for (const std::uint32_t factor : node.operands)
        if (nodes_[factor].kind == Kind::constant && nodes_[factor].value < 0.0) negative = !negative;
    return negative;
  }
  [[nodiscard]] std::uint64_t hash_without_sign(std::uint32_t term) const {
    auto part = [this](std::uint32_t id) {
      const Node& node = nodes_[id];
      return node.kind == Kind::constant
                 ? mix(static_cast<std::uint64_t>(Kind::constant), std::bit_cast<std::uint64_t>(std::fabs(node.value)))
                 : node.hash;
    };
    if (nodes_[term].kind != Kind::multiply) return part(term);
    std::vector<std::uint32_t> factors;
    for (const std::uint32_t factor : nodes_[term].operands)
      if (nodes_[factor].kind != Kind::constant || std::fabs(nodes_[factor].value) != 1.0) factors.push_back(factor);
    if (factors.size() == 1) return part(factors.front());
    std::uint64_t hash = 0;
    for (const std::uint32_t factor : factors) hash += mix(0, part(factor));
    return hash;
  }

  // `id`, or where it is a sum whose leading term has a negative
  // coefficient, the sum with every sign flipped (`negated` toggled).
  std::uint32_t sign_normalized(std::uint32_t id, bool& negated) {
    if (nodes_[id].kind != Kind::add) return id;
    const std::vector<std::uint32_t> terms = nodes_[id].operands;
    std::uint32_t leading = terms.front();
    std::uint64_t least = hash_without_sign(leading);
    for (const std::uint32_t term : terms) {
      const std::uint64_t hash = hash_without_sign(term);
      if (hash < least) {
        least = hash;
        leading = term;
      }
    }
    if (!negative(leading)) return id;
    std::vector<std::uint32_t> flipped;
    for (const std::uint32_t term : terms)
      flipped.push_back(nodes_[term].kind == Kind::constant ? constant(-nodes_[term].value)
                                                             : product({term}, true));
    negated = !negated;
    return sum(std::move(flipped));
  }

  // The sum of `terms`: NaN where a term is the constant NaN; the constant
  // terms (GiNaC's coefficient, and constants folded from functions of
  // numbers) added into one, in their canonical order.
  std::uint32_t sum(std::vector<std::uint32_t> terms) {
    std::vector<std::uint32_t> rest, constants;
    for (const std::uint32_t term : terms) {
      if (nodes_[term].kind != Kind::constant) rest.push_back(term);
      else if (std::isnan(nodes_[term].value)) return term;
      else constants.push_back(term);
    }
    if (constants.size() > 1) {
      sort_canonically(constants);
      constants = {apply(Kind::add, std::move(constants))};
    }
    if (!constants.empty() && (nodes_[constants.front()].value != 0.0 || rest.empty()))
      rest.push_back(constants.front());
    if (rest.size() == 1) return rest.front();
    sort_canonically(rest);
    return apply(Kind::add, std::move(rest));
  }

  // The product of `factors`, negated where asked: NaN where a factor is
  // the constant NaN; nested products flattened; the signs of every constant gathered into one, carried by
  // the first constant other than 1 (in the canonical order of their
  // magnitudes) or standing as one constant −1; a sign of +1 left out. Only
  // signs are folded, so that no product of constants overflows (π·1e308
  // stays two factors, as written), and a product whose signs GiNaC put on
  // other constants (−1e17·(−π) or 1e17·π) is written one way.
  std::uint32_t product(const std::vector<std::uint32_t>& factors, bool negated) {
    bool negative = negated;
    bool has_nan = false;  // then the product is NaN
    std::vector<std::uint32_t> rest, magnitudes;
    auto take = [&](std::uint32_t factor) {
      const Node& node = nodes_[factor];
      if (node.kind != Kind::constant) {
        rest.push_back(factor);
        return;
      }
      has_nan = has_nan || std::isnan(node.value);
      if (node.value < 0.0) negative = !negative;
      if (std::fabs(node.value) != 1.0) magnitudes.push_back(constant(std::fabs(node.value)));
    };
    for (const std::uint32_t factor : factors) {
      if (nodes_[factor].kind == Kind::multiply) {
        const std::vector<std::uint32_t> inner = nodes_[factor].operands;
        for (const std::uint32_t f : inner) take(f);
      } else {
        take(factor);
      }
    }
    if (has_nan) return constant(std::numeric_limits<double>::quiet_NaN());
    sort_canonically(magnitudes);
    if (negative && !magnitudes.empty()) magnitudes.front() = constant(-nodes_[magnitudes.front()].value);
    else if (negative || (rest.empty() && magnitudes.empty())) magnitudes.push_back(constant(negative ? -1.0 : 1.0));
    rest.insert(rest.end(), magnitudes.begin(), magnitudes.end());
    if (rest.size() == 1) return rest[0];
    sort_canonically(rest);
    return apply(Kind::multiply, std::move(rest));
  }

  // The id of `node`: the one already stored with its structure, or a new one.
  std::uint32_t store(Node node) {
    std::uint64_t hash = mix(static_cast<std::uint64_t>(node.kind), node.index);
    hash = mix(hash, std::bit_cast<std::uint64_t>(node.value));
    for (const std::uint32_t operand : node.operands) hash = mix(hash, nodes_[operand].hash);
    node.hash = hash;
    const auto [first, last] = by_hash_.equal_range(hash);
    for (auto candidate = first; candidate != last; ++candidate) {
      const Node& known = nodes_[candidate->second];
      if (same_leaf(known, node) && known.operands == node.operands) return candidate->second;
    }
    operations_ += std::max<std::size_t>(node.operands.size(), 2) - 1;
    if (operations_ > max_operations_)
      throw std::length_error("more than " + std::to_string(max_operations_) + " operations");
    nodes_.push_back(std::move(node));
    const auto id = static_cast<std::uint32_t>(nodes_.size() - 1);
    by_hash_.emplace(hash, id);
    return id;
  }

  std::size_t max_operations_;
  std::size_t operations_ = 0;  // leaves count 1, a sum or product of n operands n − 1
  std::vector<Node> nodes_;
  std::unordered_multimap<std::uint64_t, std::uint32_t> by_hash_;
  std::unordered_map<const GiNaC::basic*, std::uint32_t> by_address_;
  std::vector<GiNaC::ex> held_;
};

}  // namespace

std::string_view c_function_name(Kind kind) {
  if (kind == Kind::abs) return "fabs";
  for (const auto& [name, known] : unary_functions)
    if (known == kind) return name;
  return {};
}

KernelCode kernel_code(const std::vector<GiNaC::ex>& outputs, std::size_t max_operations) {
  Interner interner(max_operations);
  std::vector<std::uint32_t> roots;
  for (const GiNaC::ex& output : outputs) roots.push_back(interner.intern(output));

  // the operations in the order a depth-first walk from out[0], out[1], ...
  // meets them, each after its operands: an order of the structure alone
  KernelCode code;
  std::unordered_map<std::uint32_t, std::uint32_t> operation_of;
  std::vector<std::pair<std::uint32_t, std::size_t>> pending;  // node, next operand to visit
  for (const std::uint32_t root : roots) {
    if (!operation_of.contains(root)) pending.emplace_back(root, 0);
    while (!pending.empty()) {
      auto& [id, next] = pending.back();
      if (operation_of.contains(id)) {  // reached meanwhile through another operand
        pending.pop_back();
        continue;
      }
      const Node& node = interner.node(id);
      if (next < node.operands.size()) {
        const std::uint32_t operand = node.operands[next++];
        if (!operation_of.contains(operand)) pending.emplace_back(operand, 0);
        continue;
      }
      KernelOperation operation;
      operation.kind = node.kind;
      operation.index = node.index;
      operation.value = node.value;
      for (const std::uint32_t operand : node.operands) operation.operands.push_back(operation_of.at(operand));
      operation_of.emplace(id, static_cast<std::uint32_t>(code.operations.size()));
      code.operations.push_back(std::move(operation));
      pending.pop_back();
    }
    code.outputs.push_back(operation_of.at(root));
  }
  return code;
}

}  // namespace impactlab
