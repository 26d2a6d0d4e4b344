// Names, C types and constants of an OpenCL translation (opencl_scope.hpp).
#include "glsl/opencl_scope.hpp"

#include "glsl/opencl_helpers.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include <cmath>
#include <cstdint>

namespace clmarch::glsl::opencl {

std::string parenthesised(const std::string& text, int precedence, int wanted) {
  return precedence < wanted ? std::string("(") + text + ")" : text;
}

std::string negated(const std::string& text, int precedence) {
  return std::string("-") + (text[0] == '-' ? std::string("(") + text + ")" : parenthesised(text, precedence, kUnary));
}

char component_letter(int index) { return "xyzw"[index]; }

const char* same_opencl_function(Builtin builtin) {
  switch (builtin) {
    case Builtin::Radians:
      return "radians";
    case Builtin::Degrees:
      return "degrees";
    case Builtin::Sin:
      return "sin";
    case Builtin::Cos:
      return "cos";
    case Builtin::Tan:
      return "tan";
    case Builtin::Asin:
      return "asin";
    case Builtin::Acos:
      return "acos";
    case Builtin::Atan:
      return "atan";
    case Builtin::Sinh:
      return "sinh";
    case Builtin::Cosh:
      return "cosh";
    case Builtin::Tanh:
      return "tanh";
    case Builtin::Asinh:
      return "asinh";
    case Builtin::Acosh:
      return "acosh";
    case Builtin::Atanh:
      return "atanh";
    case Builtin::Exp:
      return "exp";
    case Builtin::Log:
      return "log";
    case Builtin::Exp2:
      return "exp2";
    case Builtin::Log2:
      return "log2";
    case Builtin::Sqrt:
      return "sqrt";
    case Builtin::InverseSqrt:
      return "rsqrt";
    case Builtin::Floor:
      return "floor";
    case Builtin::Trunc:
      return "trunc";
    // GLSL lets round() take halves either way; Mesa's llvmpipe (the renders' ground truth)
    // rounds them to even, as rint does.
    case Builtin::Round:
    case Builtin::RoundEven:
      return "rint";
    case Builtin::Ceil:
      return "ceil";
    case Builtin::Min:
      return "min";
    case Builtin::Max:
      return "max";
    default:
      return nullptr;
  }
}

const char* c_symbol(Operator op) {
  switch (op) {
    case Operator::Add:
      return "+";
    case Operator::Subtract:
      return "-";
    case Operator::Multiply:
      return "*";
    case Operator::Divide:
      return "/";
    case Operator::Modulo:
      return "%";
    case Operator::ShiftLeft:
      return "<<";
    case Operator::ShiftRight:
      return ">>";
    case Operator::BitwiseAnd:
      return "&";
    case Operator::BitwiseOr:
      return "|";
    case Operator::BitwiseXor:
      return "^";
    case Operator::Less:
      return "<";
    case Operator::Greater:
      return ">";
    case Operator::LessEqual:
      return "<=";
    case Operator::GreaterEqual:
      return ">=";
    case Operator::Equal:
      return "==";
    case Operator::NotEqual:
      return "!=";
    default:
      throw std::logic_error("opencl translation: an operator C does not spell alike");
  }
}

Scope::Scope(const Module& module, const TranslationOptions& options) : module_(module), options_(options) {}

std::string Scope::unique_name(const std::string& wanted) {
  const std::string base = options_.prefix + "_" + wanted;
  std::string name = base;
  for (int n = 2; taken_.count(name) != 0; ++n) name = fmt::format("{}_{}", base, n);
  taken_.insert(name);
  return name;
}

std::string Scope::glsl_name(const Type& type) const {
  if (type.is_array()) return fmt::format("{}_array{}", glsl_name(type.element()), type.array_size);
  if (type.is_struct()) return module_.structs[type.struct_index].name;
  if (type.is_matrix()) {
    return type.rows == type.columns ? fmt::format("mat{}", type.columns)
                                     : fmt::format("mat{}x{}", type.columns, type.rows);
  }
  const char* scalar = "void";
  const char* vector = "";
  switch (type.scalar) {
    case Scalar::Float:
      scalar = "float", vector = "vec";
      break;
    case Scalar::Int:
      scalar = "int", vector = "ivec";
      break;
    case Scalar::Uint:
      scalar = "uint", vector = "uvec";
      break;
    case Scalar::Bool:
      scalar = "bool", vector = "bvec";
      break;
    case Scalar::Void:
      break;
  }
  return type.rows == 1 ? scalar : fmt::format("{}{}", vector, type.rows);
}

std::string Scope::type(const Type& type) {
  if (type.is_array() || type.is_struct() || type.is_matrix()) return define_aggregate(type);
  std::string scalar;
  switch (type.scalar) {
    case Scalar::Float:
      scalar = real();
      break;
    case Scalar::Int:
      scalar = "int";
      break;
    case Scalar::Uint:
      scalar = "uint";
      break;
    // OpenCL C has no bool vectors: bvecN is intN holding GLSL's 0 and 1.
    case Scalar::Bool:
      scalar = type.rows == 1 ? "bool" : "int";
      break;
    case Scalar::Void:
      return "void";
  }
  return type.rows == 1 ? scalar : fmt::format("{}{}", scalar, type.rows);
}

// Matrices, structs and arrays are C structs, so that they copy by value as GLSL's values do.
std::string Scope::define_aggregate(const Type& type) {
  const std::string key = glsl_name(type);
  if (auto found = aggregate_names_.find(key); found != aggregate_names_.end()) return found->second;
  std::string body;
  if (type.is_array()) {
    body = fmt::format("  {} e[{}];\n", this->type(type.element()), type.array_size);
  } else if (type.is_struct()) {
    const StructType& s = module_.structs[type.struct_index];
    for (size_t i = 0; i < s.members.size(); ++i) {
      const Type& member = s.members[i].type;
      body += fmt::format("  {} {};\n", this->type(member), member_name(type, static_cast<int>(i)));
    }
  } else {
    Type column;
    column.scalar = type.scalar;
    column.rows = type.rows;
    body = fmt::format("  {} c[{}];\n", this->type(column), type.columns);
  }
  const std::string name = unique_name(key);
  aggregate_names_[key] = name;
  definitions_.push_back(fmt::format("typedef struct {{\n{}}} {};\n", body, name));
  return name;
}

// A suffix keeps user names apart from OpenCL C's keywords, built-ins and macros (`half`,
// `local`, `M_PI`) and from the kernels' names, none of which ends with an underscore.
std::string Scope::member_name(const Type& struct_type, int member) const {
  return module_.structs[struct_type.struct_index].members[member].name + "_";
}

namespace {

// The shortest decimal that reads back as the same float (or double), with a point or exponent.
std::string shortest_decimal(double value, bool as_float) {
  std::string text = as_float ? fmt::format("{}", static_cast<float>(value)) : fmt::format("{}", value);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

}  // namespace

std::string Scope::scalar_literal(double value, Scalar scalar) const {
  switch (scalar) {
    case Scalar::Bool:
      return value != 0.0 ? "true" : "false";
    case Scalar::Int: {
      const auto i = static_cast<std::int64_t>(value);
      // -2147483648 would be the negation of a literal too large for int.
      return i == INT32_MIN ? "(-2147483647 - 1)" : fmt::format("{}", i);
    }
    case Scalar::Uint:
      return fmt::format("{}u", static_cast<std::uint32_t>(value));
    case Scalar::Void:
      return "";
    case Scalar::Float:
      break;
  }
  const bool single = !options_.double_precision;
  if (std::isnan(value)) return single ? "NAN" : "(double)NAN";
  if (std::isinf(value)) {
    const std::string infinity = single ? "INFINITY" : "(double)INFINITY";
    return value < 0 ? std::string("(-") + infinity + ")" : infinity;
  }
  const double rounded = single ? static_cast<double>(static_cast<float>(value)) : value;
  return shortest_decimal(rounded, single) + (single ? "f" : "");
}

int Scope::flattened_size(const Type& type) const {
  int element = type.components();
  if (type.is_struct()) {
    element = 0;
    for (const StructMember& member : module_.structs[type.struct_index].members) {
      element += flattened_size(member.type);
    }
  }
  return type.is_array() ? element * type.array_size : element;
}

std::string Scope::constant(const Type& type, const double* components, int* precedence) {
  *precedence = kPostfix;
  if (is_single_scalar(type)) {
    std::string text = scalar_literal(components[0], type.scalar);
    if (text[0] == '-') *precedence = kUnary;
    return text;
  }
  if (is_single_vector(type)) {
    std::vector<std::string> parts;
    bool uniform = true;
    for (int i = 0; i < type.rows; ++i) {
      // bvec components are intN's: 0 and 1.
      const Scalar scalar = type.scalar == Scalar::Bool ? Scalar::Int : type.scalar;
      parts.push_back(scalar_literal(components[i], scalar));
      uniform = uniform && components[i] == components[0];
    }
    *precedence = kUnary;
    return fmt::format("({})({})", this->type(type), uniform ? parts[0] : fmt::format("{}", fmt::join(parts, ", ")));
  }
  // Matrices, structs and arrays: their constructor from their parts, each part a constant.
  std::vector<Type> part_types;
  if (type.is_array()) {
    part_types.assign(type.array_size, type.element());
  } else if (type.is_struct()) {
    for (const StructMember& member : module_.structs[type.struct_index].members) part_types.push_back(member.type);
  } else {
    Type column;
    column.scalar = type.scalar;
    column.rows = type.rows;
    part_types.assign(type.columns, column);
  }
  std::vector<std::string> parts;
  for (const Type& part : part_types) {
    int unused = 0;
    parts.push_back(constant(part, components, &unused));
    components += flattened_size(part);
  }
  return fmt::format("{}({})", constructor_helper(*this, type, part_types), fmt::join(parts, ", "));
}

std::string Scope::zero(const Type& type) {
  if (is_single_scalar(type)) return scalar_literal(0.0, type.scalar);
  if (is_single_vector(type)) {
    return fmt::format("({})({})", this->type(type),
                       scalar_literal(0.0, type.scalar == Scalar::Bool ? Scalar::Int : type.scalar));
  }
  return zero_helper(*this, type) + "()";
}

std::string Scope::helper(const std::string& wanted, const std::function<std::string(const std::string&)>& define) {
  if (auto found = helpers_.find(wanted); found != helpers_.end()) return found->second;
  const std::string name = unique_name(wanted);
  helpers_[wanted] = name;
  std::string definition = define(name);
  definitions_.push_back(std::move(definition));
  return name;
}

}  // namespace clmarch::glsl::opencl
