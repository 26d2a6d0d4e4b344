// GLSL's built-in functions in the OpenCL translation (opencl_emitter.hpp): OpenCL C's built-in
// where it means what GLSL's does, a helper (opencl_helpers.hpp) where it does not.
#include "glsl/opencl_emitter.hpp"
#include "glsl/opencl_helpers.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace clmarch::glsl::opencl {

Value FunctionEmitter::builtin(const Expr& expr, Lines& pre) {
  const std::vector<Expr>& operands = expr.operands;
  const Type& x = operands[0].type;
  if (expr.builtin == Builtin::Modf) {
    return call_with_places(modf_helper(scope_, x), {}, {&operands[0], &operands[1]},
                            {ParameterQualifier::In, ParameterQualifier::Out}, expr.type, pre);
  }
  std::vector<const Expr*> arguments;
  for (const Expr& operand : operands) arguments.push_back(&operand);
  std::vector<Value> v = in_order(arguments, pre);
  std::vector<std::string> texts;
  for (const Value& value : v) texts.push_back(value.text);
  auto call = [&](const std::string& function) {
    return Value{fmt::format("{}({})", function, fmt::join(texts, ", "))};
  };
  const std::string n = x.rows == 1 ? "" : std::to_string(x.rows);
  const bool scalar = x.rows == 1;
  const bool single = !scope_.options().double_precision;
  auto relational = [&](const char* symbol) {
    return Value{fmt::format("-convert_int{}({} {} {})", n, parenthesised(texts[0], v[0].precedence, kShift), symbol,
                             parenthesised(texts[1], v[1].precedence, kShift)),
                 kUnary};
  };
  if (const char* function = same_opencl_function(expr.builtin)) return call(function);
  switch (expr.builtin) {
    case Builtin::Atan2:
      return scalar ? call("atan2") : call(componentwise_helper(scope_, "atan2", x));
    case Builtin::Pow:
      return scalar ? call("pow") : call(componentwise_helper(scope_, "pow", x));
    case Builtin::Abs:
      // OpenCL's abs of an int is a uint (abs(INT_MIN) = 2^31); GLSL's stays an int.
      if (x.scalar == Scalar::Int) return Value{fmt::format("as_int{}(abs({}))", n, texts[0])};
      return call("fabs");
    case Builtin::Sign:
      if (x.scalar == Scalar::Int) return call(integer_sign_helper(scope_, x));
      return call("sign");
    case Builtin::Fract:
      return call(fract_helper(scope_, x));
    case Builtin::Mod:
      return call(mod_helper(scope_, x, operands[1].type));
    case Builtin::Clamp:
      return Value{fmt::format("min(max({}, {}), {})", texts[0], texts[1], texts[2])};
    case Builtin::Mix:
      if (operands[2].type.scalar == Scalar::Bool) {
        if (scalar) {
          // ?: evaluates one branch: every argument with side effects is read first.
          for (size_t i = 0; i < v.size(); ++i) {
            if (has_effects(operands[i]) && !v[i].stable) texts[i] = temporary(v[i], operands[i].type, pre).text;
          }
          return Value{fmt::format("{} ? {} : {}", parenthesised(texts[2], v[2].precedence, kLogicalOr),
                                   parenthesised(texts[1], v[1].precedence, kAssignment),
                                   parenthesised(texts[0], v[0].precedence, kConditional)),
                       kConditional};
        }
        // select() tests the mask's sign bit, a mask as wide as the elements (long for double).
        const std::string mask = single ? negated(texts[2], v[2].precedence)
                                        : fmt::format("convert_long{}({})", n, negated(texts[2], v[2].precedence));
        return Value{fmt::format("select({}, {}, {})", texts[0], texts[1], mask)};
      }
      return call(mix_helper(scope_, x, operands[2].type));
    case Builtin::Step:
      return call(step_helper(scope_, operands[0].type, operands[1].type));
    case Builtin::SmoothStep:
      return call(smoothstep_helper(scope_, x, operands[2].type));
    case Builtin::IsNan:
    case Builtin::IsInf: {
      const char* test = expr.builtin == Builtin::IsNan ? "isnan" : "isinf";
      if (scalar) return call(test);
      return Value{fmt::format("-convert_int{}({}({}))", n, test, texts[0]), kUnary};
    }
    case Builtin::FloatBitsToInt:
    case Builtin::FloatBitsToUint: {
      // The bits of the float GLSL holds: a double rounds to float first.
      const char* as = expr.builtin == Builtin::FloatBitsToInt ? "as_int" : "as_uint";
      if (single) return Value{fmt::format("{}{}({})", as, n, texts[0])};
      if (scalar) return Value{fmt::format("{}((float){})", as, parenthesised(texts[0], v[0].precedence, kUnary))};
      return Value{fmt::format("{}{}(convert_float{}({}))", as, n, n, texts[0])};
    }
    case Builtin::IntBitsToFloat:
    case Builtin::UintBitsToFloat:
      if (single) return Value{fmt::format("as_float{}({})", n, texts[0])};
      if (scalar) return Value{fmt::format("(double)as_float({})", texts[0]), kUnary};
      return Value{fmt::format("convert_double{}(as_float{}({}))", n, n, texts[0])};
    case Builtin::Length:
      return call(scalar ? "fabs" : "length");
    case Builtin::Distance:
      if (scalar) {
        return Value{fmt::format("fabs({} - {})", texts[0], parenthesised(texts[1], v[1].precedence, kMultiplicative))};
      }
      return call("distance");
    case Builtin::Dot:
      if (scalar) {
        return Value{fmt::format("{} * {}", parenthesised(texts[0], v[0].precedence, kMultiplicative),
                                 parenthesised(texts[1], v[1].precedence, kUnary)),
                     kMultiplicative};
      }
      return call("dot");
    case Builtin::Cross:
      return call("cross");
    case Builtin::Normalize:
      return call(scalar ? "sign" : "normalize");
    case Builtin::FaceForward:
      return call(faceforward_helper(scope_, x));
    case Builtin::Reflect:
      return call(reflect_helper(scope_, x));
    case Builtin::Refract:
      return call(refract_helper(scope_, x));
    case Builtin::MatrixCompMult:
      return call(matrix_componentwise_helper(scope_, Operator::Multiply, x, x));
    case Builtin::OuterProduct:
      return call(outer_product_helper(scope_, x, operands[1].type));
    case Builtin::Transpose:
      return call(transpose_helper(scope_, x));
    case Builtin::Determinant:
      return call(determinant_helper(scope_, x));
    case Builtin::Inverse:
      return call(inverse_helper(scope_, x));
    // Vector comparisons give -1 for true; a bvec holds 1.
    case Builtin::LessThan:
      return relational("<");
    case Builtin::LessThanEqual:
      return relational("<=");
    case Builtin::GreaterThan:
      return relational(">");
    case Builtin::GreaterThanEqual:
      return relational(">=");
    case Builtin::Equal:
      return relational("==");
    case Builtin::NotEqual:
      return relational("!=");
    // any() and all() test sign bits: a bvec's 1 is compared with 0 first.
    case Builtin::Any:
      return Value{fmt::format("any({} != 0)", parenthesised(texts[0], v[0].precedence, kRelational))};
    case Builtin::All:
      return Value{fmt::format("all({} != 0)", parenthesised(texts[0], v[0].precedence, kRelational))};
    case Builtin::Not:
      return Value{fmt::format("{} ^ 1", parenthesised(texts[0], v[0].precedence, kBitAnd)), kBitXor};
    case Builtin::Modf:
      break;
    default:  // the built-ins same_opencl_function names, returned above
      break;
  }
  throw std::logic_error("opencl translation: unknown built-in");
}

}  // namespace clmarch::glsl::opencl
