// Helper functions of an OpenCL translation (opencl_helpers.hpp).
#include "glsl/opencl_helpers.hpp"

#include <fmt/format.h>

namespace clmarch::glsl::opencl {

Type column_type(const Type& matrix) {
  Type column;
  column.scalar = matrix.scalar;
  column.rows = matrix.rows;
  return column;
}

Type with_scalar(const Type& shape, Scalar scalar) {
  Type type = shape;
  type.scalar = scalar;
  return type;
}

namespace {

// "float_float_vec2" as "2xfloat_vec2": a mat4 of 16 floats keeps a readable name.
std::string joined_names(Scope& scope, const std::vector<Type>& types) {
  std::vector<std::string> parts;
  for (size_t i = 0; i < types.size();) {
    size_t run = i;
    while (run < types.size() && types[run] == types[i]) ++run;
    const std::string name = scope.glsl_name(types[i]);
    parts.push_back(run - i > 1 ? fmt::format("{}x{}", run - i, name) : name);
    i = run;
  }
  return parts.empty() ? "nothing" : fmt::format("{}", fmt::join(parts, "_"));
}

// A function's definition from its signature's parts and its body's lines.
std::string function_text(const std::string& result, const std::string& name, const std::vector<std::string>& params,
                          const std::vector<std::string>& body) {
  std::string text =
      fmt::format("{} {}({}) {{\n", result, name, params.empty() ? "void" : fmt::format("{}", fmt::join(params, ", ")));
  for (const std::string& line : body) text += std::string("  ") + line + "\n";
  return text + "}\n";
}

// Component i of a value of `type` read from `text`: a scalar is its only component.
std::string component(const Type& type, const std::string& text, int i) {
  return type.rows == 1 ? text : fmt::format("{}.{}", text, component_letter(i));
}

std::string literal(Scope& scope, double value) { return scope.scalar_literal(value, Scalar::Float); }

// Scalar components of a constructor's argument, in GLSL's order (matrices column by column); a
// bool scalar as int, since bvecN are intN.
std::vector<std::string> flattened_components(const Type& type, const std::string& text) {
  std::vector<std::string> parts;
  if (type.is_matrix()) {
    for (int c = 0; c < type.columns; ++c) {
      for (int r = 0; r < type.rows; ++r) parts.push_back(fmt::format("{}.c[{}].{}", text, c, component_letter(r)));
    }
  } else if (type.rows == 1) {
    parts.push_back(type.scalar == Scalar::Bool ? std::string("(int)") + text : text);
  } else {
    for (int r = 0; r < type.rows; ++r) parts.push_back(component(type, text, r));
  }
  return parts;
}

std::vector<std::string> matrix_from_args(Scope& scope, const Type& target, const std::vector<Type>& args) {
  const std::string column = scope.type(column_type(target));
  const std::string zero = scope.scalar_literal(0.0, target.scalar);
  const std::string one = scope.scalar_literal(1.0, target.scalar);
  std::vector<std::string> body{fmt::format("{} r;", scope.type(target))};
  if (args.size() == 1 && args[0].is_scalar()) {
    // A diagonal matrix.
    for (int c = 0; c < target.columns; ++c) {
      std::vector<std::string> rows;
      for (int r = 0; r < target.rows; ++r) rows.push_back(r == c ? "a0" : zero);
      body.push_back(fmt::format("r.c[{}] = ({})({});", c, column, fmt::join(rows, ", ")));
    }
  } else if (args.size() == 1 && args[0].is_matrix()) {
    // The overlap of the argument, the identity's elements elsewhere.
    for (int c = 0; c < target.columns; ++c) {
      std::vector<std::string> rows;
      for (int r = 0; r < target.rows; ++r) {
        const bool inside = c < args[0].columns && r < args[0].rows;
        rows.push_back(inside ? fmt::format("a0.c[{}].{}", c, component_letter(r)) : r == c ? one : zero);
      }
      body.push_back(fmt::format("r.c[{}] = ({})({});", c, column, fmt::join(rows, ", ")));
    }
  } else {
    std::vector<std::string> parts;
    for (size_t i = 0; i < args.size(); ++i) {
      for (std::string& part : flattened_components(args[i], fmt::format("a{}", i))) parts.push_back(std::move(part));
    }
    for (int c = 0; c < target.columns; ++c) {
      std::vector<std::string> rows(parts.begin() + c * target.rows, parts.begin() + (c + 1) * target.rows);
      body.push_back(fmt::format("r.c[{}] = ({})({});", c, column, fmt::join(rows, ", ")));
    }
  }
  body.push_back("return r;");
  return body;
}

}  // namespace

std::string constructor_helper(Scope& scope, const Type& target, const std::vector<Type>& args) {
  const std::string wanted = fmt::format("{}_from_{}", scope.glsl_name(target), joined_names(scope, args));
  return scope.helper(wanted, [&](const std::string& name) {
    std::vector<std::string> params;
    for (size_t i = 0; i < args.size(); ++i) params.push_back(fmt::format("{} a{}", scope.type(args[i]), i));
    const std::string result = scope.type(target);
    std::vector<std::string> body;
    if (target.is_matrix()) {
      body = matrix_from_args(scope, target, args);
    } else if (target.is_struct() || target.is_array()) {
      body.push_back(result + " r;");
      for (size_t i = 0; i < args.size(); ++i) {
        const std::string place =
            target.is_array() ? fmt::format("e[{}]", i) : scope.member_name(target, static_cast<int>(i));
        body.push_back(fmt::format("r.{} = a{};", place, i));
      }
      body.push_back("return r;");
    } else {
      std::vector<std::string> parts;
      for (size_t i = 0; i < args.size(); ++i) {
        for (std::string& part : flattened_components(args[i], fmt::format("a{}", i))) parts.push_back(std::move(part));
      }
      parts.resize(target.rows);
      body.push_back(fmt::format("return ({})({});", result, fmt::join(parts, ", ")));
    }
    return function_text(result, name, params, body);
  });
}

std::string zero_helper(Scope& scope, const Type& type) {
  return scope.helper(std::string("zero_") + scope.glsl_name(type), [&](const std::string& name) {
    const std::string result = scope.type(type);
    std::vector<std::string> body{result + " r;"};
    if (type.is_array()) {
      body.push_back(
          fmt::format("for (int i = 0; i < {}; ++i) r.e[i] = {};", type.array_size, scope.zero(type.element())));
    } else if (type.is_struct()) {
      const auto& members = scope.module().structs[type.struct_index].members;
      for (size_t i = 0; i < members.size(); ++i) {
        body.push_back(
            fmt::format("r.{} = {};", scope.member_name(type, static_cast<int>(i)), scope.zero(members[i].type)));
      }
    } else {
      body.push_back(
          fmt::format("for (int i = 0; i < {}; ++i) r.c[i] = {};", type.columns, scope.zero(column_type(type))));
    }
    body.push_back("return r;");
    return function_text(result, name, {}, body);
  });
}

std::string vector_at_helper(Scope& scope, const Type& vector) {
  return scope.helper(scope.glsl_name(vector) + "_at", [&](const std::string& name) {
    std::string choice = fmt::format("v.{}", component_letter(vector.rows - 1));
    for (int i = vector.rows - 2; i >= 0; --i) {
      choice = fmt::format("i {} {} ? v.{} : {}", i == 0 ? "<=" : "==", i, component_letter(i), choice);
    }
    // A bvec's components are ints.
    const Type scalar{vector.scalar == Scalar::Bool ? Scalar::Int : vector.scalar};
    return function_text(scope.type(scalar), name, {scope.type(vector) + " v", "int i"},
                         {std::string("return ") + choice + ";"});
  });
}

std::string vector_with_helper(Scope& scope, const Type& vector) {
  return scope.helper(scope.glsl_name(vector) + "_with", [&](const std::string& name) {
    const Scalar scalar = vector.scalar == Scalar::Bool ? Scalar::Int : vector.scalar;
    std::vector<std::string> body;
    for (int i = 0; i < vector.rows; ++i) {
      const std::string set = fmt::format("v.{} = x;", component_letter(i));
      if (i == 0)
        body.push_back(fmt::format("if (i <= 0) {}", set));
      else if (i + 1 < vector.rows)
        body.push_back(fmt::format("else if (i == {}) {}", i, set));
      else
        body.push_back(std::string("else ") + set);
    }
    body.push_back("return v;");
    return function_text(scope.type(vector), name,
                         {scope.type(vector) + " v", "int i", scope.type(Type{scalar}) + " x"}, body);
  });
}

std::string matrix_times_vector_helper(Scope& scope, const Type& matrix) {
  return scope.helper(scope.glsl_name(matrix) + "_times_vector", [&](const std::string& name) {
    Type vector = column_type(matrix);
    vector.rows = matrix.columns;
    std::vector<std::string> terms;
    for (int c = 0; c < matrix.columns; ++c) terms.push_back(fmt::format("m.c[{}] * v.{}", c, component_letter(c)));
    return function_text(scope.type(column_type(matrix)), name, {scope.type(matrix) + " m", scope.type(vector) + " v"},
                         {fmt::format("return {};", fmt::join(terms, " + "))});
  });
}

std::string vector_times_matrix_helper(Scope& scope, const Type& matrix) {
  return scope.helper(std::string("vector_times_") + scope.glsl_name(matrix), [&](const std::string& name) {
    Type result = column_type(matrix);
    result.rows = matrix.columns;
    std::vector<std::string> dots;
    for (int c = 0; c < matrix.columns; ++c) dots.push_back(fmt::format("dot(v, m.c[{}])", c));
    return function_text(scope.type(result), name, {scope.type(column_type(matrix)) + " v", scope.type(matrix) + " m"},
                         {fmt::format("return ({})({});", scope.type(result), fmt::join(dots, ", "))});
  });
}

std::string matrix_times_matrix_helper(Scope& scope, const Type& a, const Type& b) {
  return scope.helper(fmt::format("{}_times_{}", scope.glsl_name(a), scope.glsl_name(b)), [&](const std::string& name) {
    Type result = a;
    result.columns = b.columns;
    const std::string times = matrix_times_vector_helper(scope, a);
    std::vector<std::string> body{scope.type(result) + " r;"};
    for (int c = 0; c < b.columns; ++c) body.push_back(fmt::format("r.c[{}] = {}(a, b.c[{}]);", c, times, c));
    body.push_back("return r;");
    return function_text(scope.type(result), name, {scope.type(a) + " a", scope.type(b) + " b"}, body);
  });
}

std::string matrix_componentwise_helper(Scope& scope, Operator op, const Type& a, const Type& b) {
  const char* word = op == Operator::Add        ? "plus"
                     : op == Operator::Subtract ? "minus"
                     : op == Operator::Multiply ? "times"
                                                : "over";
  const char* symbol = op == Operator::Add        ? "+"
                       : op == Operator::Subtract ? "-"
                       : op == Operator::Multiply ? "*"
                                                  : "/";
  // matrixCompMult: not the linear-algebra product matrix_times_matrix_helper names a_times_b.
  const bool both = a.is_matrix() && b.is_matrix();
  const std::string wanted = both && op == Operator::Multiply
                                 ? "matrixCompMult_" + scope.glsl_name(a)
                                 : fmt::format("{}_{}_{}", scope.glsl_name(a), word, scope.glsl_name(b));
  return scope.helper(wanted, [&](const std::string& name) {
    const Type& matrix = a.is_matrix() ? a : b;
    std::vector<std::string> body{scope.type(matrix) + " r;"};
    for (int c = 0; c < matrix.columns; ++c) {
      const std::string left = a.is_matrix() ? fmt::format("a.c[{}]", c) : "a";
      const std::string right = b.is_matrix() ? fmt::format("b.c[{}]", c) : "b";
      body.push_back(fmt::format("r.c[{}] = {} {} {};", c, left, symbol, right));
    }
    body.push_back("return r;");
    return function_text(scope.type(matrix), name, {scope.type(a) + " a", scope.type(b) + " b"}, body);
  });
}

std::string matrix_negate_helper(Scope& scope, const Type& matrix) {
  return scope.helper(std::string("negate_") + scope.glsl_name(matrix), [&](const std::string& name) {
    std::vector<std::string> body;
    for (int c = 0; c < matrix.columns; ++c) body.push_back(fmt::format("m.c[{}] = -m.c[{}];", c, c));
    body.push_back("return m;");
    return function_text(scope.type(matrix), name, {scope.type(matrix) + " m"}, body);
  });
}

std::string transpose_helper(Scope& scope, const Type& matrix) {
  return scope.helper(std::string("transpose_") + scope.glsl_name(matrix), [&](const std::string& name) {
    Type result = matrix;
    result.rows = matrix.columns;
    result.columns = matrix.rows;
    std::vector<std::string> body{scope.type(result) + " r;"};
    for (int c = 0; c < result.columns; ++c) {
      std::vector<std::string> rows;
      for (int r = 0; r < result.rows; ++r) rows.push_back(fmt::format("m.c[{}].{}", r, component_letter(c)));
      body.push_back(fmt::format("r.c[{}] = ({})({});", c, scope.type(column_type(result)), fmt::join(rows, ", ")));
    }
    body.push_back("return r;");
    return function_text(scope.type(result), name, {scope.type(matrix) + " m"}, body);
  });
}

namespace {

// The determinant of m's elements in `rows` x `columns` (equal counts), by cofactor expansion
// along the first row.
std::string minor_determinant(const std::vector<int>& rows, const std::vector<int>& columns) {
  auto element = [](int r, int c) { return fmt::format("m.c[{}].{}", c, component_letter(r)); };
  if (rows.size() == 1) return element(rows[0], columns[0]);
  if (rows.size() == 2) {
    return fmt::format("{} * {} - {} * {}", element(rows[0], columns[0]), element(rows[1], columns[1]),
                       element(rows[0], columns[1]), element(rows[1], columns[0]));
  }
  std::string text;
  const std::vector<int> rest_rows(rows.begin() + 1, rows.end());
  for (size_t i = 0; i < columns.size(); ++i) {
    std::vector<int> rest_columns = columns;
    rest_columns.erase(rest_columns.begin() + static_cast<long>(i));
    text += fmt::format("{} {} * ({})",
                        i == 0       ? ""
                        : i % 2 == 0 ? " +"
                                     : " -",
                        element(rows[0], columns[i]), minor_determinant(rest_rows, rest_columns));
  }
  return text.substr(1);
}

std::vector<int> all_but(int count, int skipped) {
  std::vector<int> indices;
  for (int i = 0; i < count; ++i) {
    if (i != skipped) indices.push_back(i);
  }
  return indices;
}

}  // namespace

std::string determinant_helper(Scope& scope, const Type& matrix) {
  return scope.helper(std::string("determinant_") + scope.glsl_name(matrix), [&](const std::string& name) {
    return function_text(
        scope.real(), name, {scope.type(matrix) + " m"},
        {fmt::format("return {};", minor_determinant(all_but(matrix.rows, -1), all_but(matrix.rows, -1)))});
  });
}

// The adjugate over the determinant: column c of the inverse holds the cofactors of m's column c
// taken as rows.
std::string inverse_helper(Scope& scope, const Type& matrix) {
  return scope.helper(std::string("inverse_") + scope.glsl_name(matrix), [&](const std::string& name) {
    const int n = matrix.rows;
    std::vector<std::string> body{fmt::format("{} d = {}(m);", scope.real(), determinant_helper(scope, matrix)),
                                  scope.type(matrix) + " r;"};
    for (int c = 0; c < n; ++c) {
      std::vector<std::string> cofactors;
      for (int r = 0; r < n; ++r) {
        // inverse[c][r] = cofactor(row c, column r) / d.
        const std::string minor =
            n == 2 ? minor_determinant({1 - c}, {1 - r}) : minor_determinant(all_but(n, c), all_but(n, r));
        cofactors.push_back((c + r) % 2 == 0 ? minor : fmt::format("-({})", minor));
      }
      body.push_back(
          fmt::format("r.c[{}] = ({})({}) / d;", c, scope.type(column_type(matrix)), fmt::join(cofactors, ", ")));
    }
    body.push_back("return r;");
    return function_text(scope.type(matrix), name, {scope.type(matrix) + " m"}, body);
  });
}

std::string outer_product_helper(Scope& scope, const Type& column, const Type& row) {
  return scope.helper(
      fmt::format("outer_product_{}_{}", scope.glsl_name(column), scope.glsl_name(row)), [&](const std::string& name) {
        Type result = column;
        result.columns = row.rows;
        std::vector<std::string> body{scope.type(result) + " r;"};
        for (int c = 0; c < row.rows; ++c) body.push_back(fmt::format("r.c[{}] = c * r_.{};", c, component_letter(c)));
        body.push_back("return r;");
        return function_text(scope.type(result), name, {scope.type(column) + " c", scope.type(row) + " r_"}, body);
      });
}

std::string equal_expression(Scope& scope, const Type& type, const std::string& a, const std::string& b) {
  if (is_single_scalar(type)) return fmt::format("{} == {}", a, b);
  if (is_single_vector(type)) return fmt::format("all({} == {})", a, b);
  const std::string equal = scope.helper(std::string("equal_") + scope.glsl_name(type), [&](const std::string& name) {
    std::vector<std::string> body;
    if (type.is_array()) {
      body.push_back(fmt::format("for (int i = 0; i < {}; ++i) {{", type.array_size));
      body.push_back(
          fmt::format("  if (!({})) return false;", equal_expression(scope, type.element(), "a.e[i]", "b.e[i]")));
      body.push_back("}");
      body.push_back("return true;");
    } else {
      std::vector<std::string> terms;
      if (type.is_struct()) {
        const auto& members = scope.module().structs[type.struct_index].members;
        for (size_t i = 0; i < members.size(); ++i) {
          const std::string member = scope.member_name(type, static_cast<int>(i));
          terms.push_back(
              equal_expression(scope, members[i].type, std::string("a.") + member, std::string("b.") + member));
        }
      } else {
        for (int c = 0; c < type.columns; ++c) terms.push_back(fmt::format("all(a.c[{}] == b.c[{}])", c, c));
      }
      body.push_back(fmt::format("return {};", fmt::join(terms, " && ")));
    }
    return function_text("bool", name, {scope.type(type) + " a", scope.type(type) + " b"}, body);
  });
  return fmt::format("{}({}, {})", equal, a, b);
}

std::string integer_divide_helper(Scope& scope, Operator op, const Type& a, const Type& b) {
  const bool divide = op == Operator::Divide;
  const std::string wanted =
      fmt::format("{}_{}_{}", divide ? "divide" : "remainder", scope.glsl_name(a), scope.glsl_name(b));
  return scope.helper(wanted, [&](const std::string& name) {
    const Type result = a.rows >= b.rows ? a : b;
    std::vector<std::string> body;
    if (result.is_scalar()) {
      const bool is_signed = result.scalar == Scalar::Int;
      if (divide && is_signed) {
        body = {"if (b == 0) return 0;", "if (b == -1) return as_int(0u - as_uint(a));", "return a / b;"};
      } else if (is_signed) {
        body = {"if (b == 0 || b == -1) return 0;", "return a % b;"};
      } else {
        body = {fmt::format("return b == 0u ? 0u : a {} b;", divide ? "/" : "%")};
      }
    } else {
      const std::string scalar = integer_divide_helper(scope, op, Type{result.scalar}, Type{result.scalar});
      std::vector<std::string> parts;
      for (int i = 0; i < result.rows; ++i)
        parts.push_back(fmt::format("{}({}, {})", scalar, component(a, "a", i), component(b, "b", i)));
      body.push_back(fmt::format("return ({})({});", scope.type(result), fmt::join(parts, ", ")));
    }
    return function_text(scope.type(result), name, {scope.type(a) + " a", scope.type(b) + " b"}, body);
  });
}

std::string fract_helper(Scope& scope, const Type& x) {
  return scope.helper(std::string("fract_") + scope.glsl_name(x), [&](const std::string& name) {
    return function_text(scope.type(x), name, {scope.type(x) + " x"}, {"return x - floor(x);"});
  });
}

// pow and atan2 one component at a time, through their scalar names: for one lane of double the
// kernels redefine those names as macros of scalars (kernels/lanes.cl), and a vector call fails.
std::string componentwise_helper(Scope& scope, const char* function, const Type& x) {
  return scope.helper(fmt::format("{}_{}", function, scope.glsl_name(x)), [&](const std::string& name) {
    std::string components;
    for (int i = 0; i < x.rows; ++i) {
      const char axis = "xyzw"[i];
      components += fmt::format("{}{}(a.{}, b.{})", i ? ", " : "", function, axis, axis);
    }
    return function_text(scope.type(x), name, {scope.type(x) + " a", scope.type(x) + " b"},
                         {fmt::format("return ({})({});", scope.type(x), components)});
  });
}

// GLSL's step, 0 where x < edge and 1 elsewhere, written without OpenCL's step, which the kernels
// redefine for one lane of double (kernels/lanes.cl) as a macro of scalars.
std::string step_helper(Scope& scope, const Type& edge, const Type& x) {
  return scope.helper(
      fmt::format("step_{}_{}", scope.glsl_name(edge), scope.glsl_name(x)), [&](const std::string& name) {
        const std::string zero = literal(scope, 0.0), one = literal(scope, 1.0);
        const std::string body =
            x.rows == 1 ? fmt::format("return x < edge ? {} : {};", zero, one)
                        : fmt::format("return select(({0})({1}), ({0})({2}), x < edge);", scope.type(x), one, zero);
        return function_text(scope.type(x), name, {scope.type(edge) + " edge", scope.type(x) + " x"}, {body});
      });
}

// GLSL's mod is floor-based (OpenCL's fmod truncates, so negative x differ).
std::string mod_helper(Scope& scope, const Type& x, const Type& y) {
  return scope.helper(fmt::format("mod_{}_{}", scope.glsl_name(x), scope.glsl_name(y)), [&](const std::string& name) {
    return function_text(scope.type(x), name, {scope.type(x) + " x", scope.type(y) + " y"},
                         {"return x - y * floor(x / y);"});
  });
}

// GLSL's x (1 - a) + y a, for every a (OpenCL's mix is x + (y - x) a, undefined outside [0, 1]).
std::string mix_helper(Scope& scope, const Type& x, const Type& a) {
  return scope.helper(fmt::format("mix_{}_{}", scope.glsl_name(x), scope.glsl_name(a)), [&](const std::string& name) {
    return function_text(scope.type(x), name, {scope.type(x) + " x", scope.type(x) + " y", scope.type(a) + " a"},
                         {fmt::format("return x * ({} - a) + y * a;", literal(scope, 1.0))});
  });
}

// GLSL's formula for any edges (OpenCL leaves edge0 >= edge1 undefined; shaders use it reversed).
std::string smoothstep_helper(Scope& scope, const Type& edge, const Type& x) {
  return scope.helper(
      fmt::format("smoothstep_{}_{}", scope.glsl_name(edge), scope.glsl_name(x)), [&](const std::string& name) {
        return function_text(scope.type(x), name,
                             {scope.type(edge) + " edge0", scope.type(edge) + " edge1", scope.type(x) + " x"},
                             {fmt::format("{} t = min(max((x - edge0) / (edge1 - edge0), {}), {});", scope.type(x),
                                          literal(scope, 0.0), literal(scope, 1.0)),
                              fmt::format("return t * t * ({} - {} * t);", literal(scope, 3.0), literal(scope, 2.0))});
      });
}

std::string integer_sign_helper(Scope& scope, const Type& x) {
  return scope.helper(std::string("sign_") + scope.glsl_name(x), [&](const std::string& name) {
    // Vector comparisons give -1 for true, scalar ones 1.
    const std::string body = x.rows == 1 ? "return (x > 0) - (x < 0);" : "return (x < 0) - (x > 0);";
    return function_text(scope.type(x), name, {scope.type(x) + " x"}, {body});
  });
}

namespace {

std::string dot_text(const Type& type, const std::string& a, const std::string& b) {
  return type.rows == 1 ? fmt::format("{} * {}", a, b) : fmt::format("dot({}, {})", a, b);
}

}  // namespace

std::string faceforward_helper(Scope& scope, const Type& n) {
  return scope.helper(std::string("faceforward_") + scope.glsl_name(n), [&](const std::string& name) {
    const std::string t = scope.type(n);
    return function_text(t, name, {t + " n", t + " i", t + " nref"},
                         {fmt::format("return {} < {} ? n : -n;", dot_text(n, "nref", "i"), literal(scope, 0.0))});
  });
}

std::string reflect_helper(Scope& scope, const Type& i) {
  return scope.helper(std::string("reflect_") + scope.glsl_name(i), [&](const std::string& name) {
    const std::string t = scope.type(i);
    return function_text(t, name, {t + " i", t + " n"},
                         {fmt::format("return i - {} * {} * n;", literal(scope, 2.0), dot_text(i, "n", "i"))});
  });
}

std::string refract_helper(Scope& scope, const Type& i) {
  return scope.helper(std::string("refract_") + scope.glsl_name(i), [&](const std::string& name) {
    const std::string t = scope.type(i);
    const std::string one = literal(scope, 1.0);
    return function_text(
        t, name, {t + " i", t + " n", scope.real() + " eta"},
        {fmt::format("{} d = {};", scope.real(), dot_text(i, "n", "i")),
         fmt::format("{} k = {} - eta * eta * ({} - d * d);", scope.real(), one, one),
         fmt::format("return k < {} ? {} : eta * i - (eta * d + sqrt(k)) * n;", literal(scope, 0.0), scope.zero(i))});
  });
}

std::string modf_helper(Scope& scope, const Type& x) {
  return scope.helper(std::string("modf_") + scope.glsl_name(x), [&](const std::string& name) {
    const std::string t = scope.type(x);
    return function_text(t, name, {t + " x", t + "* whole"}, {"*whole = trunc(x);", "return x - *whole;"});
  });
}

std::string float_to_uint_helper(Scope& scope, const Type& x) {
  return scope.helper(std::string("uint_from_") + scope.glsl_name(x), [&](const std::string& name) {
    const Type result = with_scalar(x, Scalar::Uint);
    const std::string zero = literal(scope, 0.0);
    std::string body;
    if (x.rows == 1) {
      body = fmt::format("return x < {} ? as_uint(convert_int_sat_rtz(x)) : convert_uint_sat_rtz(x);", zero);
    } else {
      // The mask as intN whatever the precision (double comparisons give longN).
      body = fmt::format(
          "return select(convert_uint{0}_sat_rtz(x), as_uint{0}(convert_int{0}_sat_rtz(x)), convert_int{0}(x < {1}));",
          x.rows, zero);
    }
    return function_text(scope.type(result), name, {scope.type(x) + " x"}, {body});
  });
}

}  // namespace clmarch::glsl::opencl
