#include <impactlab/oscillators/model_file/model_expression.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cctype>
#include <vector>

namespace impactlab {

namespace {

constexpr std::array<ExpressionFunction, 15> functions = {{
    {"sin", 1}, {"cos", 1}, {"tan", 1}, {"asin", 1}, {"acos", 1}, {"atan", 1}, {"atan2", 2},
    {"sinh", 1}, {"cosh", 1}, {"tanh", 1}, {"exp", 1}, {"log", 1}, {"sqrt", 1}, {"abs", 1},
    {"pow", 2},
}};

const ExpressionFunction* find_function(std::string_view name) {
  for (const auto& spec : functions)
    if (spec.name == name) return &spec;
  return nullptr;
}

GiNaC::ex apply_function(std::string_view name, const std::vector<GiNaC::ex>& a) {
  if (name == "sin") return GiNaC::sin(a[0]);
  if (name == "cos") return GiNaC::cos(a[0]);
  if (name == "tan") return GiNaC::tan(a[0]);
  if (name == "asin") return GiNaC::asin(a[0]);
  if (name == "acos") return GiNaC::acos(a[0]);
  if (name == "atan") return GiNaC::atan(a[0]);
  if (name == "atan2") return GiNaC::atan2(a[0], a[1]);
  if (name == "sinh") return GiNaC::sinh(a[0]);
  if (name == "cosh") return GiNaC::cosh(a[0]);
  if (name == "tanh") return GiNaC::tanh(a[0]);
  if (name == "exp") return GiNaC::exp(a[0]);
  if (name == "log") return GiNaC::log(a[0]);
  if (name == "sqrt") return GiNaC::sqrt(a[0]);
  if (name == "abs") return GiNaC::abs(a[0]);
  return GiNaC::pow(a[0], a[1]);  // pow
}

// A recursive-descent parser over one expression string.
class Parser {
 public:
  Parser(const ExpressionText& expression, const NameResolver& resolve, std::size_t depth)
      : expression_(expression), text_(expression.text), resolve_(resolve), base_depth_(depth),
        depth_(depth), deepest_(depth) {}

  ParsedExpression parse() {
    skip_space();
    if (at_end()) fail(0, "empty expression");
    GiNaC::ex result = parse_sum();
    skip_space();
    if (!at_end()) fail(position_, "unexpected '" + std::string(1, text_[position_]) + "'");
    return {result, deepest_ - base_depth_};
  }

 private:
  [[noreturn]] void fail(std::size_t at, const std::string& message) const {
    throw ModelFileError(expression_.position.advanced(at), expression_.key,
                         message + " in " + expression_.key + " = \"" + text_ + "\"");
  }
  [[nodiscard]] bool at_end() const { return position_ >= text_.size(); }
  void skip_space() {
    while (!at_end() && std::isspace(static_cast<unsigned char>(text_[position_]))) ++position_;
  }
  bool accept(std::string_view token) {
    skip_space();
    if (text_.compare(position_, token.size(), token) != 0) return false;
    position_ += token.size();
    return true;
  }

  // GiNaC evaluates as it builds; a power of zero with a negative exponent throws
  template <class Build>
  GiNaC::ex guarded(std::size_t at, Build&& build) const {
    try {
      return build();
    } catch (const std::exception&) {
      fail(at, "division by an expression that is always zero");
    }
  }

  GiNaC::ex parse_sum() {
    GiNaC::ex result = parse_product();
    for (;;) {
      if (accept("+")) result = result + parse_product();
      else if (accept("-")) result = result - parse_product();
      else return result;
    }
  }

  GiNaC::ex parse_product() {
    GiNaC::ex result = parse_unary();
    for (;;) {
      skip_space();
      // '**' is a power, handled below
      if (text_.compare(position_, 2, "**") == 0) return result;
      const std::size_t operator_at = position_;
      if (accept("*")) {
        result = result * parse_unary();
      } else if (accept("/")) {
        const GiNaC::ex denominator = parse_unary();
        // zero as GiNaC evaluates it (x - x); not expanded, which can take
        // unbounded time: a denominator zero only once expanded makes the
        // expression infinite, refused at the initial state
        if (denominator.is_zero())
          fail(operator_at, "division by an expression that is always zero");
        result = guarded(operator_at, [&] { return result / denominator; });
      } else {
        return result;
      }
    }
  }

  // one nesting level more, down to `at`, the place that goes too deep
  void reach(std::size_t depth, std::size_t at) {
    if (depth > max_expression_nesting)
      fail(at, "nested deeper than " + std::to_string(max_expression_nesting) +
                   " levels (parentheses, functions, signs, powers, through definitions)");
    deepest_ = std::max(deepest_, depth);
  }

  // every path of the recursion passes here: the one place that counts levels
  GiNaC::ex parse_unary() {
    skip_space();
    reach(++depth_, position_);
    GiNaC::ex result;
    if (accept("-")) result = -parse_unary();
    else if (accept("+")) result = parse_unary();
    else result = parse_power();
    --depth_;
    return result;
  }

  // base^exponent, refused (at `at`) for zero to the power zero or to a
  // negative power, for an integer exponent beyond max_integer_exponent,
  // and where GiNaC would raise an exact number in the base to a power whose
  // digits no computation can hold: it computes such powers exactly
  // (pow(sqrt(3), 1e5)^1e5, or ((1e308*x)^1000)^1000, ran for minutes).
  void check_power(std::size_t at, const GiNaC::ex& base, const GiNaC::ex& exponent) const {
    // refused before GiNaC throws for them, which leaks the power it was building
    if (base.is_zero() && exponent.is_zero()) fail(at, "zero to the power zero is undefined");
    if (base.is_zero() && exponent.info(GiNaC::info_flags::negative))
      fail(at, "division by an expression that is always zero");
    if (!GiNaC::is_a<GiNaC::numeric>(exponent) || !exponent.info(GiNaC::info_flags::rational)) return;
    const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(exponent);
    if (n.is_integer() && GiNaC::abs(n) > max_integer_exponent)
      fail(at, "an integer exponent beyond ±" + std::to_string(max_integer_exponent));
    if (raised_number_bits(base, std::fabs(n.to_double())) > max_exact_power_bits)
      fail(at, "a number raised to a power too large to compute exactly");
  }

  // The binary digits GiNaC computes for the exact numbers in `base` raised
  // to a power of magnitude `power`: a rational a/b gives a^power and
  // b^power, a power c^m raises c to |m|·power, a product raises each
  // factor (the largest counts); sums and functions are not raised.
  static double raised_number_bits(const GiNaC::ex& base, double power) {
    if (GiNaC::is_a<GiNaC::numeric>(base)) {
      const GiNaC::numeric& c = GiNaC::ex_to<GiNaC::numeric>(base);
      if (!c.is_rational()) return 0.0;
      return static_cast<double>(std::max(c.numer().int_length(), c.denom().int_length())) * power;
    }
    if (GiNaC::is_a<GiNaC::power>(base) && GiNaC::is_a<GiNaC::numeric>(base.op(1)))
      return raised_number_bits(base.op(0), std::fabs(GiNaC::ex_to<GiNaC::numeric>(base.op(1)).to_double()) * power);
    double most = 0.0;
    if (GiNaC::is_a<GiNaC::mul>(base))
      for (std::size_t i = 0; i < base.nops(); ++i) most = std::max(most, raised_number_bits(base.op(i), power));
    return most;
  }

  GiNaC::ex parse_power() {
    const GiNaC::ex base = parse_primary();
    skip_space();
    const std::size_t operator_at = position_;
    if (accept("**") || accept("^")) {
      const GiNaC::ex exponent = parse_unary();
      check_power(operator_at, base, exponent);
      return guarded(operator_at, [&] { return GiNaC::pow(base, exponent); });
    }
    return base;
  }

  GiNaC::ex parse_primary() {
    skip_space();
    if (at_end()) fail(position_, "expression ends too early");
    const char c = text_[position_];
    if (c == '(') {
      ++position_;
      GiNaC::ex inner = parse_sum();
      if (!accept(")")) fail(position_, "expected ')'");
      return inner;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return parse_number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return parse_name();
    fail(position_, "unexpected '" + std::string(1, c) + "'");
  }

  // A decimal number, kept exact: digits × 10^exponent as a GiNaC rational.
  GiNaC::ex parse_number() {
    const std::size_t start = position_;
    std::string digits;
    long exponent = 0;
    bool seen_digit = false;
    while (!at_end() && std::isdigit(static_cast<unsigned char>(text_[position_]))) {
      digits += text_[position_++];
      seen_digit = true;
    }
    if (!at_end() && text_[position_] == '.') {
      ++position_;
      while (!at_end() && std::isdigit(static_cast<unsigned char>(text_[position_]))) {
        digits += text_[position_++];
        --exponent;
        seen_digit = true;
      }
    }
    if (!seen_digit) fail(start, "malformed number");
    if (!at_end() && (text_[position_] == 'e' || text_[position_] == 'E')) {
      std::size_t cursor = position_ + 1;
      int sign = 1;
      if (cursor < text_.size() && (text_[cursor] == '+' || text_[cursor] == '-')) {
        sign = text_[cursor] == '-' ? -1 : 1;
        ++cursor;
      }
      if (cursor >= text_.size() || !std::isdigit(static_cast<unsigned char>(text_[cursor])))
        fail(position_, "malformed exponent");
      long written = 0;
      while (cursor < text_.size() && std::isdigit(static_cast<unsigned char>(text_[cursor]))) {
        written = std::min(written * 10 + (text_[cursor] - '0'), 100000L);
        ++cursor;
      }
      if (written > 400) fail(position_, "exponent out of range");
      exponent += sign * written;
      position_ = cursor;
    }
    const GiNaC::numeric mantissa(digits.c_str());
    const GiNaC::numeric value = mantissa * GiNaC::pow(GiNaC::numeric(10), GiNaC::numeric(exponent));
    if (!std::isfinite(value.to_double())) fail(start, "a number beyond the range of a double");
    return value;
  }

  GiNaC::ex parse_name() {
    const std::size_t start = position_;
    while (!at_end() && (std::isalnum(static_cast<unsigned char>(text_[position_])) ||
                         text_[position_] == '_'))
      ++position_;
    const std::string name = text_.substr(start, position_ - start);
    skip_space();
    if (!at_end() && text_[position_] == '(') {
      const ExpressionFunction* spec = find_function(name);
      if (!spec) fail(start, "unknown function '" + name + "'");
      ++position_;
      std::vector<GiNaC::ex> arguments;
      skip_space();
      if (!accept(")")) {
        do {
          arguments.push_back(parse_sum());
        } while (accept(","));
        if (!accept(")")) fail(position_, "expected ',' or ')'");
      }
      if (arguments.size() != spec->arity)
        fail(start, "function '" + name + "' takes " + std::to_string(spec->arity) +
                        " argument(s), given " + std::to_string(arguments.size()));
      if (name == "pow") check_power(start, arguments[0], arguments[1]);
      return guarded(start, [&] { return apply_function(name, arguments); });
    }
    if (name == "pi") return GiNaC::Pi;
    if (find_function(name)) fail(start, "function '" + name + "' needs arguments");
    const auto resolved = resolve_(name, expression_.position.advanced(start), depth_);
    if (!resolved) fail(start, "unknown symbol '" + name + "'");
    reach(depth_ + resolved->height, start);
    return resolved->value;
  }

  const ExpressionText& expression_;
  const std::string& text_;
  const NameResolver& resolve_;
  std::size_t position_ = 0;
  std::size_t base_depth_;  // the nesting level the expression starts at
  std::size_t depth_;       // the nesting level now
  std::size_t deepest_;     // the deepest level reached, through definitions too
};

}  // namespace

ParsedExpression parse_expression(const ExpressionText& expression, const NameResolver& resolve,
                                  std::size_t depth) {
  return Parser(expression, resolve, depth).parse();
}

bool is_reserved_name(std::string_view name) {
  return name == "pi" || name == "t" || find_function(name) != nullptr;
}

std::span<const ExpressionFunction> expression_functions() { return functions; }

}  // namespace impactlab
