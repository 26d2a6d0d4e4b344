// GLSL's built-in functions in the packet translation (packet_emitter.hpp), with the meaning the
// lane-at-a-time translation gives them (opencl_builtins.cpp).
#include "glsl/packet_emitter.hpp"

#include <algorithm>
#include <functional>

namespace clmarch::glsl::packets {

PacketValue PacketEmitter::builtin(const Expr& expr, Lines& pre) {
  if (expr.builtin == Builtin::Modf) unsupported(expr.location, "modf");
  const std::vector<PacketValue> v = in_order(expr.operands, pre);
  for (const PacketValue& value : v) {
    if (value.kind == Kind::Mask) unsupported(expr.location, "a built-in of bools of the point");
  }
  for (const Expr& operand : expr.operands) {
    if (!is_real(operand.type) && expr.builtin != Builtin::Abs && expr.builtin != Builtin::Min &&
        expr.builtin != Builtin::Max && expr.builtin != Builtin::Clamp) {
      unsupported(expr.location, "a built-in of integers or bools");
    }
  }
  const bool uniform = std::all_of(v.begin(), v.end(), [](const PacketValue& x) { return x.kind == Kind::Uniform; });
  // An argument's component as the result's type wants it: a scalar where all are uniform.
  auto arg = [&](size_t k, size_t i) { return uniform ? component(v[k], i) : packet(v[k], i); };
  const size_t n = std::max<size_t>(1, static_cast<size_t>(is_real(expr.type) ? expr.type.components() : 1));
  auto each = [&](const std::function<std::string(size_t)>& text) {
    PacketValue value{{}, uniform ? Kind::Uniform : Kind::Packet, true};
    for (size_t i = 0; i < n; ++i) value.c.push_back(uniform ? fmt::format("({})", text(i)) : text(i));
    if (uniform) {
      value.stable = false;
      return value;
    }
    return bound(value, pre);
  };
  auto function = [&](const char* name) {
    return each([&](size_t i) {
      std::vector<std::string> texts;
      for (size_t k = 0; k < v.size(); ++k) texts.push_back(arg(k, i));
      return fmt::format("{}({})", name, fmt::join(texts, ", "));
    });
  };
  // A sum over the components of the first argument's size.
  const size_t width = v[0].c.size();
  auto sum = [&](const std::function<std::string(size_t)>& term) {
    std::vector<std::string> terms;
    for (size_t i = 0; i < width; ++i) terms.push_back(term(i));
    return fmt::format("{}", fmt::join(terms, " + "));
  };
  auto scalar = [&](const std::string& text) {
    return uniform ? PacketValue{{fmt::format("({})", text)}, Kind::Uniform, false}
                   : bound(PacketValue{{text}, Kind::Packet, true}, pre);
  };
  const std::string one = literal(1.0), zero = literal(0.0);
  if (const char* same = opencl::same_opencl_function(expr.builtin)) return function(same);
  switch (expr.builtin) {
    case Builtin::Atan2:
      return function("atan2");
    case Builtin::Pow:
      return function("pow");
    case Builtin::Abs:
      if (expr.type.scalar == Scalar::Int)
        return PacketValue{{fmt::format("as_int(abs({}))", v[0].c[0])}, Kind::Uniform, false};
      return function("fabs");
    case Builtin::Sign:
      return function("sign");
    case Builtin::Fract:
      return each([&](size_t i) { return fmt::format("{0} - floor({0})", arg(0, i)); });
    case Builtin::Mod:
      return each([&](size_t i) { return fmt::format("{0} - {1} * floor({0} / {1})", arg(0, i), arg(1, i)); });
    case Builtin::Clamp:
      return each([&](size_t i) { return fmt::format("min(max({}, {}), {})", arg(0, i), arg(1, i), arg(2, i)); });
    case Builtin::Mix:
      if (expr.operands[2].type.scalar == Scalar::Bool) unsupported(expr.location, "mix with a bool choice");
      return each(
          [&](size_t i) { return fmt::format("{0} * ({1} - {2}) + {3} * {2}", arg(0, i), one, arg(2, i), arg(1, i)); });
    case Builtin::Step:
      return each([&](size_t i) {
        return uniform ? fmt::format("{} < {} ? {} : {}", arg(1, i), arg(0, i), zero, one)
                       : fmt::format("select((vfloat)({}), (vfloat)({}), {} < {})", one, zero, arg(1, i), arg(0, i));
      });
    case Builtin::SmoothStep: {
      PacketValue t{{}, uniform ? Kind::Uniform : Kind::Packet, true};
      for (size_t i = 0; i < n; ++i) {
        const std::string text = fmt::format("min(max(({} - {}) / ({} - {}), {}), {})", arg(2, i), arg(0, i), arg(1, i),
                                             arg(0, i), zero, one);
        t.c.push_back(temporary(uniform ? "real" : "vfloat", text, pre));
      }
      return each(
          [&](size_t i) { return fmt::format("{0} * {0} * ({1} - {2} * {0})", t.c[i], literal(3.0), literal(2.0)); });
    }
    // GLSL's formulas, sqrt(dot(x, x)): the lane translation calls OpenCL's length and normalize,
    // which rescale to survive components past 1e19 or below 1e-19; distance functions do not
    // reach those, and a rescale per component would cost every packet two divisions.
    case Builtin::Length:
      return scalar(fmt::format("sqrt({})", sum([&](size_t i) { return fmt::format("{0} * {0}", arg(0, i)); })));
    case Builtin::Distance: {
      PacketValue d = arithmetic(Operator::Subtract, expr.operands[0].type, v[0], v[1], pre);
      return scalar(fmt::format("sqrt({})", sum([&](size_t i) { return fmt::format("{0} * {0}", d.c[i]); })));
    }
    case Builtin::Dot:
      return scalar(sum([&](size_t i) { return fmt::format("{} * {}", arg(0, i), arg(1, i)); }));
    case Builtin::Cross:
      return each([&](size_t i) {
        const size_t j = (i + 1) % 3, k = (i + 2) % 3;
        return fmt::format("{} * {} - {} * {}", arg(0, j), arg(1, k), arg(0, k), arg(1, j));
      });
    case Builtin::Normalize: {
      const PacketValue length =
          scalar(fmt::format("sqrt({})", sum([&](size_t i) { return fmt::format("{0} * {0}", arg(0, i)); })));
      return each([&](size_t i) { return fmt::format("{} / {}", arg(0, i), length.c[0]); });
    }
    case Builtin::Reflect: {
      const PacketValue d = scalar(sum([&](size_t i) { return fmt::format("{} * {}", arg(1, i), arg(0, i)); }));
      return each(
          [&](size_t i) { return fmt::format("{} - {} * {} * {}", arg(0, i), literal(2.0), d.c[0], arg(1, i)); });
    }
    case Builtin::OuterProduct:
      return each([&](size_t i) {
        const size_t rows = static_cast<size_t>(expr.type.rows);
        return fmt::format("{} * {}", arg(0, i % rows), arg(1, i / rows));
      });
    case Builtin::MatrixCompMult:
      return each([&](size_t i) { return fmt::format("{} * {}", arg(0, i), arg(1, i)); });
    case Builtin::Transpose: {
      const Type& m = expr.operands[0].type;
      return each([&](size_t i) {
        const size_t column = i / m.columns, row = i % m.columns;
        return arg(0, row * m.rows + column);
      });
    }
    default:
      unsupported(expr.location, "this built-in function");
  }
}

}  // namespace clmarch::glsl::packets
