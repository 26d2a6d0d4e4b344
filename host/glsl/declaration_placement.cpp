// Placing locals' declarations where the source declares them.
#include "glsl/declaration_placement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <optional>
#include <string>
#include <utility>

namespace clmarch::glsl {
namespace {

/// A place in the file, ordered by line then column.
using Place = std::pair<int, int>;

Place place_of(const SourceLocation& location) { return {location.line, location.column}; }

/// The first and last places of a subtree.
struct Extent {
  Place first{INT_MAX, INT_MAX};
  Place last{0, 0};

  void add(const SourceLocation& location) {
    if (location.line <= 0) return;
    first = std::min(first, place_of(location));
    last = std::max(last, place_of(location));
  }
};

void extend(Extent& extent, const Expr& expr) {
  extent.add(expr.location);
  for (const Expr& operand : expr.operands) extend(extent, operand);
}

void extend(Extent& extent, const Stmt& statement) {
  extent.add(statement.location);
  extend(extent, statement.expression);
  extend(extent, statement.step);
  for (const Stmt& inner : statement.body) extend(extent, inner);
}

Extent extent_of(const Stmt& statement) {
  Extent extent;
  extend(extent, statement);
  return extent;
}

void collect_uses(const Expr& expr, int variable, std::vector<Place>& uses) {
  if (expr.kind == ExprKind::Variable && expr.variable == variable && expr.location.line > 0) {
    uses.push_back(place_of(expr.location));
  }
  for (const Expr& operand : expr.operands) collect_uses(operand, variable, uses);
}

void collect_uses(const Stmt& statement, int variable, std::vector<Place>& uses) {
  collect_uses(statement.expression, variable, uses);
  collect_uses(statement.step, variable, uses);
  for (const Stmt& inner : statement.body) collect_uses(inner, variable, uses);
}

/// The type as GLSL spells it in a declaration.
std::string glsl_type_name(const Type& type, const Module& module) {
  if (type.is_struct()) return module.structs[type.struct_index].name;
  const char* prefix = type.scalar == Scalar::Int    ? "i"
                       : type.scalar == Scalar::Uint ? "u"
                       : type.scalar == Scalar::Bool ? "b"
                                                     : "";
  if (type.is_matrix()) {
    return type.columns == type.rows ? fmt::format("mat{}", type.columns)
                                     : fmt::format("mat{}x{}", type.columns, type.rows);
  }
  if (type.rows > 1) return fmt::format("{}vec{}", prefix, type.rows);
  switch (type.scalar) {
    case Scalar::Int:
      return "int";
    case Scalar::Uint:
      return "uint";
    case Scalar::Bool:
      return "bool";
    default:
      return "float";
  }
}

bool is_word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

/// Whether text (one statement's start, up to a declarator's name) is a declaration of type:
/// qualifiers, the type, then declarators ("const highp float a = 1.0, ").
bool declares(std::string_view text, std::string_view type) {
  size_t at = 0;
  const auto skip_spaces = [&] {
    while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
  };
  for (;;) {
    skip_spaces();
    size_t end = at;
    while (end < text.size() && is_word_char(text[end])) ++end;
    const std::string_view word = text.substr(at, end - at);
    if (word.empty()) return false;
    at = end;
    if (word == type) break;
    if (word != "const" && word != "highp" && word != "mediump" && word != "lowp") return false;
  }
  // Nothing but the separator before the name: "float a, b" declares b after "float a, ".
  skip_spaces();
  if (at == text.size()) return true;
  const std::string_view rest = text.substr(at);
  return rest.find(',') != std::string_view::npos && rest.back() != '.';
}

/// The place where code declares a local named name of type, the nearest before first_use and
/// after the function's start, or none.
std::optional<Place> declaration_place(std::string_view code, int first_line, std::string_view name,
                                       std::string_view type, Place function_start, Place first_use) {
  std::vector<std::string_view> lines;
  for (size_t start = 0; start <= code.size();) {
    const size_t end = code.find('\n', start);
    lines.push_back(code.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  for (int line = first_use.first; line >= function_start.first; --line) {
    const int index = line - first_line;
    if (index < 0 || index >= static_cast<int>(lines.size())) continue;
    const std::string_view text = lines[index];
    size_t limit = line == first_use.first ? static_cast<size_t>(std::max(first_use.second - 1, 0)) : text.size();
    while (limit > 0) {
      const size_t at = text.rfind(name, limit - 1);
      if (at == std::string_view::npos) break;
      limit = at;
      const bool whole = (at == 0 || !is_word_char(text[at - 1])) &&
                         (at + name.size() >= text.size() || !is_word_char(text[at + name.size()]));
      if (!whole) continue;
      // The statement's start: after the last ; { } or ( before the name on this line.
      const size_t boundary = text.find_last_of(";{}(", at == 0 ? 0 : at - 1);
      const size_t start = boundary == std::string_view::npos || at == 0 ? 0 : boundary + 1;
      if (declares(text.substr(start, at - start), type)) return Place{line, static_cast<int>(at) + 1};
    }
  }
  return std::nullopt;
}

Stmt declaration_of(int variable, const Module& module) {
  Stmt declaration;
  declaration.kind = StmtKind::Declaration;
  declaration.variable = variable;
  declaration.location = module.variables[variable].location;
  return declaration;
}

/// Inserts declaration into the innermost block of statements that holds place, before the
/// first statement at or after it; false if the uses would not all follow it in that block.
bool insert_at(std::vector<Stmt>& statements, Place place, Stmt& declaration, const std::vector<Place>& uses) {
  for (size_t i = 0; i < statements.size(); ++i) {
    Stmt& statement = statements[i];
    const Extent extent = extent_of(statement);
    if (extent.first >= place) {
      // Every use must lie in this block, after the declaration.
      Extent rest;
      for (size_t j = i; j < statements.size(); ++j) extend(rest, statements[j]);
      for (const Place& use : uses) {
        if (use < rest.first || use > rest.last) return false;
      }
      statements.insert(statements.begin() + static_cast<std::ptrdiff_t>(i), std::move(declaration));
      return true;
    }
    if (extent.last >= place) {
      // place is inside this statement: a block of it holds the declaration.
      for (Stmt& inner : statement.body) {
        const Extent inner_extent = extent_of(inner);
        if (inner.kind == StmtKind::Block && inner_extent.last >= place)
          return insert_at(inner.body, place, declaration, uses);
      }
      if (statement.kind == StmtKind::Block || statement.kind == StmtKind::Switch) {
        return insert_at(statement.body, place, declaration, uses);
      }
      return false;
    }
  }
  return false;
}

}  // namespace

void place_local_declarations(Function& function, const std::vector<int>& locals, const Module& module,
                              std::string_view code, int first_line) {
  std::vector<Stmt> at_top;
  for (int local : locals) {
    std::vector<Place> uses;
    collect_uses(function.body, local, uses);
    Stmt declaration = declaration_of(local, module);
    bool placed = false;
    if (!uses.empty()) {
      const Place first_use = *std::min_element(uses.begin(), uses.end());
      const Variable& variable = module.variables[local];
      const std::optional<Place> place =
          declaration_place(code, first_line, variable.name, glsl_type_name(variable.type, module),
                            place_of(function.location), first_use);
      if (place) placed = insert_at(function.body.body, *place, declaration, uses);
    }
    if (!placed) at_top.push_back(declaration_of(local, module));
  }
  function.body.body.insert(function.body.body.begin(), std::make_move_iterator(at_top.begin()),
                            std::make_move_iterator(at_top.end()));
}

}  // namespace clmarch::glsl
