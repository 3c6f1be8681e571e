// Expressions of a model section parsed into GiNaC expressions, with the
// position of every error in the scene file.
//
// Grammar (usual precedence; ^ and ** are powers, right-associative):
//     expression := term (('+' | '-') term)*
//     term       := unary (('*' | '/') unary)*
//     unary      := ('+' | '-') unary | power
//     power      := primary (('^' | '**') unary)?
//     primary    := number | name | function '(' expression (',' expression)* ')'
//                 | '(' expression ')'
// Functions: sin cos tan asin acos atan atan2 sinh cosh tanh exp log sqrt abs pow;
// the constant pi. GiNaC's own parser reports no column, hence this one.
//
// Bounded work: every nesting level (a parenthesis, a function call, a sign,
// a power) counts, through the definitions an expression names, and an
// expression nested deeper than max_expression_nesting is refused at the
// place where it goes too deep; so is a constant that is not a finite double,
// an integer exponent beyond max_integer_exponent (C code cannot hold them),
// and a power of an exact number that would take more than
// max_exact_power_bits digits (GiNaC's exact arithmetic computes them all).
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <ginac/ginac.h>

#include <impactlab/oscillators/model_file/model_error.hpp>

namespace impactlab {

// One expression as written in the scene file.
struct ExpressionText {
  std::string key;          // where it sits in the model section, e.g. model.rhs.v
  std::string text;         // as written
  SourcePosition position;  // of its first character
};

inline constexpr std::size_t max_expression_nesting = 100;
inline constexpr long max_integer_exponent = 1024;
// the most binary digits an exact power in an expression may take (GiNaC
// computes a power of an exact number exactly: 1e308^1024 is 1.05 million)
inline constexpr double max_exact_power_bits = 4e6;

// A parsed expression and its height: the nesting levels it holds, counting
// those of the definitions it names.
struct ParsedExpression {
  GiNaC::ex value;
  std::size_t height = 0;
};

// Resolves a name to an expression (a state, a parameter, t, a definition), or
// nothing when the name is unknown. `where` is the name's position, for errors
// found while resolving it (a circular definition); `depth` the nesting level
// at which it is named (a definition parsed there starts at that depth).
using NameResolver = std::function<std::optional<ParsedExpression>(
    std::string_view name, const SourcePosition& where, std::size_t depth)>;

// The expression, or ModelFileError at the offending character: a syntax
// error, an unknown name or function, a wrong argument count, a division by an
// expression that is identically zero, nesting deeper than
// max_expression_nesting (counted from `depth`), a constant C cannot hold.
ParsedExpression parse_expression(const ExpressionText& expression, const NameResolver& resolve,
                                  std::size_t depth = 0);

// Whether `name` is taken by the expression language (a function, pi, t).
bool is_reserved_name(std::string_view name);

// A function of the expression language and its number of arguments.
struct ExpressionFunction {
  std::string_view name;
  std::size_t arity;
};

// Every function the parser accepts.
std::span<const ExpressionFunction> expression_functions();

}  // namespace impactlab
