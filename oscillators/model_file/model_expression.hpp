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
// Functions: sin cos tan asin acos atan atan2 sinh cosh tanh exp log sqrt abs;
// the constant pi. GiNaC's own parser reports no column, hence this one.
#pragma once

#include <functional>
#include <optional>
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

// Resolves a name to an expression (a state, a parameter, t, a definition), or
// nothing when the name is unknown. `where` is the name's position, for errors
// found while resolving it (a circular definition).
using NameResolver =
    std::function<std::optional<GiNaC::ex>(std::string_view name, const SourcePosition& where)>;

// The expression, or ModelFileError at the offending character: a syntax
// error, an unknown name or function, a wrong argument count, a division by an
// expression that is identically zero.
GiNaC::ex parse_expression(const ExpressionText& expression, const NameResolver& resolve);

// Whether `name` is taken by the expression language (a function, pi, t).
bool is_reserved_name(std::string_view name);

}  // namespace impactlab
