// glslang's typed tree lowered to the IR of glsl_ir.hpp. The only file that includes glslang's
// headers: its tree (intermediate.h) is internal API that later versions moved, so a change of
// glslang touches this file alone.
#include "glsl/glsl_front_end.hpp"

#include "common/errors.hpp"
#include "glsl/declaration_placement.hpp"

#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string_view>

namespace clmarch::glsl {
namespace {

using glslang::TIntermAggregate;
using glslang::TIntermBinary;
using glslang::TIntermTyped;
using glslang::TIntermUnary;
using glslang::TType;

// WebGL 2's and Shadertoy's language and uniforms. iChannel samplers are declared so that a
// lookup parses and is then refused by name rather than as an undeclared identifier.
constexpr std::string_view kPrelude =
    "#version 300 es\n"
    // Shadertoy's code initialises globals from uniforms and calls (`float t = iTime;`), which
    // WebGL accepts; GLSL ES 3.00 alone does not.
    "#extension GL_EXT_shader_non_constant_global_initializers : enable\n"
    "precision highp float;\n"
    "precision highp int;\n"
    "uniform float iTime;\n"
    "uniform vec3 iResolution;\n"
    "uniform int iFrame;\n"
    "uniform vec4 iMouse;\n"
    "uniform float iTimeDelta;\n"
    "uniform sampler2D iChannel0;\n"
    "uniform sampler2D iChannel1;\n"
    "uniform sampler2D iChannel2;\n"
    "uniform sampler2D iChannel3;\n";

void initialize_glslang_once() {
  // glslang's process-wide tables; never finalized, as other users in the process may parse too.
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

// A type as GLSL spells it: "float", "vec3", "mat2", "ivec2", a struct's name, "float[3]".
std::string type_name(const TType& type) {
  std::string name;
  switch (type.getBasicType()) {
    case glslang::EbtVoid:
      name = "void";
      break;
    case glslang::EbtStruct:
      name = type.getTypeName().c_str();
      break;
    case glslang::EbtSampler:
      name = "sampler";
      break;
    default: {
      const std::string_view prefix = type.getBasicType() == glslang::EbtInt    ? "i"
                                      : type.getBasicType() == glslang::EbtUint ? "u"
                                      : type.getBasicType() == glslang::EbtBool ? "b"
                                                                                : "";
      if (type.isMatrix()) {
        name = type.getMatrixCols() == type.getMatrixRows()
                   ? fmt::format("mat{}", type.getMatrixCols())
                   : fmt::format("mat{}x{}", type.getMatrixCols(), type.getMatrixRows());
      } else if (type.isVector()) {
        name = fmt::format("{}vec{}", prefix, type.getVectorSize());
      } else {
        name = prefix == "i" ? "int" : prefix == "u" ? "uint" : prefix == "b" ? "bool" : "float";
      }
    }
  }
  if (type.isArray()) name += fmt::format("[{}]", type.getOuterArraySize());
  return name;
}

UniformKind uniform_kind(std::string_view name) {
  if (name == "iTime") return UniformKind::Time;
  if (name == "iResolution") return UniformKind::Resolution;
  if (name == "iFrame") return UniformKind::Frame;
  if (name == "iMouse") return UniformKind::Mouse;
  if (name == "iTimeDelta") return UniformKind::TimeDelta;
  return UniformKind::None;
}

// The first of glslang's messages as "file:line:col: text": glslang prints "ERROR: file:line: text"
// without a column, so the column is where the message's first quoted token starts on that line.
std::string first_error(const std::string& log, const Source& source) {
  std::string_view rest = log;
  std::string_view line;
  while (!rest.empty()) {
    const size_t end = rest.find('\n');
    line = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    if (line.starts_with("ERROR: ")) break;
    line = {};
  }
  if (line.empty()) return fmt::format("{}: glslang refused the code: {}", source.file_name, log);
  line.remove_prefix(7);
  const std::string file_prefix = source.file_name + ":";
  if (!line.starts_with(file_prefix)) return fmt::format("{}: {}", source.file_name, line);
  std::string_view after = line.substr(file_prefix.size());
  const size_t colon = after.find(':');
  const int line_number = std::atoi(std::string(after.substr(0, colon)).c_str());
  std::string_view text = colon == std::string_view::npos ? after : after.substr(colon + 1);
  while (text.starts_with(' ')) text.remove_prefix(1);
  // A syntax error quotes no token: "'' :  syntax error, ...".
  if (text.starts_with("'' :")) text.remove_prefix(4);
  while (text.starts_with(' ')) text.remove_prefix(1);
  while (text.ends_with(' ')) text.remove_suffix(1);
  int column = 0;
  const size_t open = text.find('\'');
  const size_t close = open == std::string_view::npos ? open : text.find('\'', open + 1);
  const int code_line = line_number - source.first_line;
  if (close != std::string_view::npos && close > open + 1 && code_line >= 0) {
    size_t start = 0;
    for (int i = 0; i < code_line && start != std::string::npos; ++i) {
      start = source.code.find('\n', start);
      if (start != std::string::npos) ++start;
    }
    if (start != std::string::npos) {
      const std::string_view code_text = std::string_view(source.code).substr(start);
      const std::string_view source_line = code_text.substr(0, code_text.find('\n'));
      const size_t at = source_line.find(text.substr(open + 1, close - open - 1));
      if (at != std::string_view::npos) column = static_cast<int>(at) + 1;
    }
  }
  if (column > 0) return fmt::format("{}:{}:{}: {}", source.file_name, line_number, column, text);
  return fmt::format("{}:{}: {}", source.file_name, line_number, text);
}

// Lowers one parsed shader; each method handles one family of glslang's nodes.
class Lowering {
 public:
  Lowering(const Source& source, Module& module) : source_(source), module_(module) {}

  void run(TIntermNode* root) {
    TIntermAggregate* top = root ? root->getAsAggregate() : nullptr;
    if (!top) throw InputError(fmt::format("{}: no code", source_.file_name));
    collect_functions(top);
    const int distance = find_entry(source_.distance_function, true);
    const int color = source_.color_function.empty() ? -1 : find_entry(source_.color_function, false);
    std::vector<int> order;
    std::set<int> done;
    visit_callees(distance, order, done);
    if (color >= 0) visit_callees(color, order, done);
    // Functions lowered in callee-first order, their indices renumbered to it.
    std::map<int, int> index_of;
    for (int definition : order) index_of[definition] = static_cast<int>(index_of.size());
    lower_globals(top);
    for (int definition : order) module_.functions.push_back(lower_function(definition, index_of));
    module_.distance_function = index_of.at(distance);
    module_.color_function = color >= 0 ? index_of.at(color) : -1;
  }

 private:
  struct Definition {
    std::string mangled;
    std::string name;
    TIntermAggregate* node = nullptr;
  };

  [[noreturn]] void fail(const glslang::TSourceLoc& loc, const std::string& what) const {
    throw InputError(fmt::format("{}:{}:{}: {}", source_.file_name, loc.line, message_column(loc), what));
  }

  // glslang places a call (and a function's definition) at its closing parenthesis: a message
  // points at the function's name instead, found by matching the parentheses back on that line.
  int message_column(const glslang::TSourceLoc& loc) const {
    const int column = std::max(loc.column, 1);
    const std::string_view text = code_line(loc.line);
    size_t at = static_cast<size_t>(column - 1);
    if (at >= text.size() || text[at] != ')') return column;
    int depth = 0;
    for (;; --at) {
      if (text[at] == ')') ++depth;
      if (text[at] == '(' && --depth == 0) break;
      if (at == 0) return column;
    }
    while (at > 0 && text[at - 1] == ' ') --at;
    size_t start = at;
    while (start > 0 && (std::isalnum(static_cast<unsigned char>(text[start - 1])) || text[start - 1] == '_')) --start;
    return start < at ? static_cast<int>(start) + 1 : column;
  }

  // The text of a line of the user's code, by its number in the file.
  std::string_view code_line(int line) const {
    std::string_view code = source_.code;
    for (int i = source_.first_line; i < line; ++i) {
      const size_t end = code.find('\n');
      if (end == std::string_view::npos) return {};
      code.remove_prefix(end + 1);
    }
    return code.substr(0, code.find('\n'));
  }

  SourceLocation location(const glslang::TSourceLoc& loc) const { return {loc.line, loc.column}; }

  void collect_functions(TIntermAggregate* top) {
    for (TIntermNode* node : top->getSequence()) {
      TIntermAggregate* aggregate = node->getAsAggregate();
      if (!aggregate || aggregate->getOp() != glslang::EOpFunction) continue;
      const std::string mangled = aggregate->getName().c_str();
      definitions_.push_back({mangled, mangled.substr(0, mangled.find('(')), aggregate});
      definition_of_[mangled] = static_cast<int>(definitions_.size()) - 1;
    }
  }

  int find_entry(const std::string& name, bool distance) {
    const std::string wanted = distance ? "float, vec2, vec3 or vec4 " + name + "(vec3)" : "vec3 " + name + "(vec3)";
    bool named = false;
    for (size_t i = 0; i < definitions_.size(); ++i) {
      if (definitions_[i].name != name) continue;
      named = true;
      TIntermAggregate* node = definitions_[i].node;
      const auto& parameters = node->getSequence()[0]->getAsAggregate()->getSequence();
      if (parameters.size() != 1) continue;
      const TType& parameter = parameters[0]->getAsTyped()->getType();
      if (parameter.getBasicType() != glslang::EbtFloat || !parameter.isVector() || parameter.getVectorSize() != 3 ||
          parameter.isArray() || parameter.getQualifier().storage == glslang::EvqOut ||
          parameter.getQualifier().storage == glslang::EvqInOut) {
        continue;
      }
      const TType& result = node->getType();
      const bool float_result = result.getBasicType() == glslang::EbtFloat && !result.isMatrix() && !result.isArray();
      if (distance ? float_result : float_result && result.isVector() && result.getVectorSize() == 3) {
        return static_cast<int>(i);
      }
      fail(node->getLoc(), fmt::format("'{}' returns {}; clmarch needs {}", name, type_name(result), wanted));
    }
    if (named)
      throw InputError(fmt::format("{}: no function {} (the ones named '{}' take other parameters)", source_.file_name,
                                   wanted, name));
    throw InputError(fmt::format("{}: no function {}", source_.file_name, wanted));
  }

  // Depth-first over the calls from a definition, callees before callers.
  void visit_callees(int definition, std::vector<int>& order, std::set<int>& done) {
    if (!done.insert(definition).second) return;
    visit_calls_in(definitions_[definition].node, order, done);
    order.push_back(definition);
  }

  // visit_callees of every function node calls.
  void visit_calls_in(TIntermNode* node, std::vector<int>& order, std::set<int>& done) {
    std::vector<TIntermAggregate*> calls;
    collect_calls(node, calls);
    for (TIntermAggregate* call : calls) {
      const auto found = definition_of_.find(call->getName().c_str());
      if (found == definition_of_.end()) {
        const std::string mangled = call->getName().c_str();
        fail(call->getLoc(), fmt::format("'{}' is declared but never defined", mangled.substr(0, mangled.find('('))));
      }
      visit_callees(found->second, order, done);
    }
  }

  static void collect_calls(TIntermNode* node, std::vector<TIntermAggregate*>& calls) {
    struct CallCollector : glslang::TIntermTraverser {
      std::vector<TIntermAggregate*>* calls;
      bool visitAggregate(glslang::TVisit, TIntermAggregate* aggregate) override {
        if (aggregate->getOp() == glslang::EOpFunctionCall && aggregate->isUserDefined()) calls->push_back(aggregate);
        return true;
      }
    } collector;
    collector.calls = &calls;
    node->traverse(&collector);
  }

  Type lower_type(const TType& type, const glslang::TSourceLoc& loc) {
    Type result;
    if (type.isArray()) {
      if (type.getArraySizes()->getNumDims() != 1) fail(loc, "arrays of arrays are not GLSL ES 3.00");
      result.array_size = type.getOuterArraySize();
    }
    switch (type.getBasicType()) {
      case glslang::EbtVoid:
        result.scalar = Scalar::Void;
        return result;
      case glslang::EbtBool:
        result.scalar = Scalar::Bool;
        break;
      case glslang::EbtInt:
        result.scalar = Scalar::Int;
        break;
      case glslang::EbtUint:
        result.scalar = Scalar::Uint;
        break;
      case glslang::EbtFloat:
        result.scalar = Scalar::Float;
        break;
      case glslang::EbtStruct:
        result.struct_index = struct_index(type, loc);
        return result;
      case glslang::EbtSampler:
        fail(loc, "textures (samplers, iChannel0-3) cannot be used in a distance function: it has no texture units");
      default:
        fail(loc, fmt::format("the type {} is not supported", type_name(type)));
    }
    if (type.isMatrix()) {
      result.columns = type.getMatrixCols();
      result.rows = type.getMatrixRows();
    } else if (type.isVector()) {
      result.rows = type.getVectorSize();
    }
    return result;
  }

  int struct_index(const TType& type, const glslang::TSourceLoc& loc) {
    const glslang::TTypeList* members = type.getStruct();
    const auto found = struct_of_.find(members);
    if (found != struct_of_.end()) return found->second;
    StructType lowered;
    lowered.name = type.getTypeName().c_str();
    for (const glslang::TTypeLoc& member : *members) {
      lowered.members.push_back({member.type->getFieldName().c_str(), lower_type(*member.type, loc)});
    }
    module_.structs.push_back(std::move(lowered));
    const int index = static_cast<int>(module_.structs.size()) - 1;
    struct_of_[members] = index;
    return index;
  }

  // The variable of a symbol, declared on first sight; locals join the function being lowered.
  int variable_of(glslang::TIntermSymbol* symbol) {
    const auto found = variable_of_.find(symbol->getId());
    if (found != variable_of_.end()) return found->second;
    const TType& type = symbol->getType();
    Variable variable;
    variable.name = symbol->getName().c_str();
    variable.location = location(symbol->getLoc());
    switch (type.getQualifier().storage) {
      case glslang::EvqTemporary:
        variable.storage = Storage::Local;
        break;
      case glslang::EvqGlobal:
        variable.storage = Storage::Global;
        break;
      case glslang::EvqConst:
        variable.storage = Storage::GlobalConst;
        break;
      case glslang::EvqUniform:
        variable.storage = Storage::Uniform;
        variable.uniform = uniform_kind(variable.name);
        if (type.getBasicType() == glslang::EbtSampler) {
          fail(symbol->getLoc(), fmt::format("texture lookups ('{}') cannot be used in a distance function: it has no "
                                             "texture units",
                                             variable.name));
        }
        if (variable.uniform == UniformKind::None) {
          fail(symbol->getLoc(), fmt::format("uniform '{}': only iTime, iResolution, iFrame, iMouse and iTimeDelta are "
                                             "provided (use a const or a #define, or the scene's `defines:`)",
                                             variable.name));
        }
        break;
      default:
        fail(symbol->getLoc(), fmt::format("'{}' has no meaning in a distance function: it belongs to a fragment "
                                           "shader's pixel, and a distance function sees only its point",
                                           variable.name));
    }
    variable.type = lower_type(type, symbol->getLoc());
    module_.variables.push_back(std::move(variable));
    const int index = static_cast<int>(module_.variables.size()) - 1;
    variable_of_[symbol->getId()] = index;
    if (module_.variables[index].storage == Storage::Local && locals_) locals_->push_back(index);
    return index;
  }

  // Globals: initialised ones are assignments between the functions, the rest are linker objects;
  // const ones with a value that was not folded into every use (an array indexed at run time).
  void lower_globals(TIntermAggregate* top) {
    for (TIntermNode* node : top->getSequence()) {
      TIntermAggregate* aggregate = node->getAsAggregate();
      if (aggregate && aggregate->getOp() == glslang::EOpLinkerObjects) {
        for (TIntermNode* object : aggregate->getSequence()) declare_global(object->getAsSymbolNode(), nullptr);
      } else if (aggregate && aggregate->getOp() == glslang::EOpSequence) {
        for (TIntermNode* initializer : aggregate->getSequence()) {
          TIntermBinary* assign = initializer->getAsBinaryNode();
          if (!assign || assign->getOp() != glslang::EOpAssign || !assign->getLeft()->getAsSymbolNode()) {
            fail(initializer->getLoc(), "unexpected global statement");
          }
          declare_global(assign->getLeft()->getAsSymbolNode(), assign->getRight());
        }
      } else if (TIntermBinary* assign = node->getAsBinaryNode()) {
        if (assign->getOp() != glslang::EOpAssign || !assign->getLeft()->getAsSymbolNode()) {
          fail(node->getLoc(), "unexpected global statement");
        }
        declare_global(assign->getLeft()->getAsSymbolNode(), assign->getRight());
      }
    }
  }

  void declare_global(glslang::TIntermSymbol* symbol, TIntermTyped* initializer) {
    if (!symbol) return;
    const glslang::TStorageQualifier storage = symbol->getType().getQualifier().storage;
    // Uniforms join the module where a function reads them (so that its variables say whether the
    // code reads the time); samplers and unknown ones are refused there, with that place.
    if (storage == glslang::EvqUniform) return;
    if (storage == glslang::EvqVaryingOut || storage == glslang::EvqVaryingIn) {
      fail(symbol->getLoc(),
           fmt::format("'{}': a distance function has no shader inputs or outputs", symbol->getName().c_str()));
    }
    const bool seen = variable_of_.count(symbol->getId()) != 0;
    const int variable = variable_of(symbol);
    Stmt declaration;
    declaration.kind = StmtKind::Declaration;
    declaration.variable = variable;
    declaration.location = location(symbol->getLoc());
    if (initializer) {
      declaration.expression = lower_expr(initializer);
      declaration.has_value = true;
    } else if (storage == glslang::EvqConst && symbol->getConstArray().size() > 0) {
      declaration.expression = constant(symbol->getConstArray(), symbol->getType(), symbol->getLoc());
      declaration.has_value = true;
    }
    if (seen) {
      // A linker object listed after its initialising assignment: already declared.
      for (const Stmt& global : module_.globals) {
        if (global.variable == variable) return;
      }
    }
    module_.globals.push_back(std::move(declaration));
  }

  Function lower_function(int definition, const std::map<int, int>& index_of) {
    TIntermAggregate* node = definitions_[definition].node;
    function_index_ = &index_of;
    Function function;
    function.name = definitions_[definition].name;
    function.location = location(node->getLoc());
    function.return_type = lower_type(node->getType(), node->getLoc());
    std::vector<int> locals;
    locals_ = &locals;
    for (TIntermNode* parameter : node->getSequence()[0]->getAsAggregate()->getSequence()) {
      glslang::TIntermSymbol* symbol = parameter->getAsSymbolNode();
      Variable variable;
      variable.name = symbol->getName().c_str();
      variable.location = location(symbol->getLoc());
      variable.storage = Storage::Parameter;
      const glslang::TStorageQualifier storage = symbol->getType().getQualifier().storage;
      variable.qualifier = storage == glslang::EvqOut     ? ParameterQualifier::Out
                           : storage == glslang::EvqInOut ? ParameterQualifier::InOut
                                                          : ParameterQualifier::In;
      variable.type = lower_type(symbol->getType(), symbol->getLoc());
      module_.variables.push_back(std::move(variable));
      const int index = static_cast<int>(module_.variables.size()) - 1;
      variable_of_[symbol->getId()] = index;
      function.parameters.push_back(index);
    }
    Stmt body;
    body.kind = StmtKind::Block;
    body.location = function.location;
    if (node->getSequence().size() > 1 && node->getSequence()[1]) {
      lower_statement_into(node->getSequence()[1], body.body);
    }
    function.body = std::move(body);
    place_local_declarations(function, locals, module_, source_.code, source_.first_line);
    locals_ = nullptr;
    return function;
  }

  // Appends the statements of node to out: a sequence's statements in place, any other node as one.
  void lower_statement_into(TIntermNode* node, std::vector<Stmt>& out) {
    TIntermAggregate* aggregate = node->getAsAggregate();
    if (aggregate && (aggregate->getOp() == glslang::EOpSequence || aggregate->getOp() == glslang::EOpScope)) {
      Stmt block;
      block.kind = StmtKind::Block;
      block.location = location(node->getLoc());
      for (TIntermNode* child : aggregate->getSequence()) {
        if (child) lower_statement_into(child, block.body);
      }
      out.push_back(std::move(block));
      return;
    }
    out.push_back(lower_statement(node));
  }

  Stmt single_statement(TIntermNode* node, const glslang::TSourceLoc& loc) {
    Stmt block;
    block.kind = StmtKind::Block;
    block.location = location(loc);
    if (node) lower_statement_into(node, block.body);
    return block;
  }

  Stmt lower_statement(TIntermNode* node) {
    Stmt statement;
    statement.location = location(node->getLoc());
    if (glslang::TIntermSelection* selection = node->getAsSelectionNode();
        selection && selection->getType().getBasicType() == glslang::EbtVoid) {
      statement.kind = StmtKind::If;
      statement.expression = lower_expr(selection->getCondition());
      statement.body.push_back(single_statement(selection->getTrueBlock(), node->getLoc()));
      if (selection->getFalseBlock())
        statement.body.push_back(single_statement(selection->getFalseBlock(), node->getLoc()));
      return statement;
    }
    if (glslang::TIntermLoop* loop = node->getAsLoopNode()) {
      statement.kind = StmtKind::Loop;
      statement.test_first = loop->testFirst();
      statement.has_condition = loop->getTest() != nullptr;
      if (loop->getTest()) statement.expression = lower_expr(loop->getTest());
      statement.has_step = loop->getTerminal() != nullptr;
      if (loop->getTerminal()) statement.step = lower_expr(loop->getTerminal());
      statement.body.push_back(single_statement(loop->getBody(), node->getLoc()));
      return statement;
    }
    if (glslang::TIntermBranch* branch = node->getAsBranchNode()) {
      switch (branch->getFlowOp()) {
        case glslang::EOpReturn:
          statement.kind = StmtKind::Return;
          if (branch->getExpression()) {
            statement.expression = lower_expr(branch->getExpression());
            statement.has_value = true;
          }
          return statement;
        case glslang::EOpBreak:
          statement.kind = StmtKind::Break;
          return statement;
        case glslang::EOpContinue:
          statement.kind = StmtKind::Continue;
          return statement;
        case glslang::EOpCase:
          statement.kind = StmtKind::Case;
          statement.expression = lower_expr(branch->getExpression());
          statement.has_value = true;
          return statement;
        case glslang::EOpDefault:
          statement.kind = StmtKind::Case;
          return statement;
        case glslang::EOpKill:
        case glslang::EOpTerminateInvocation:
        case glslang::EOpDemote:
          fail(node->getLoc(), "'discard' cannot be used in a distance function: it has no fragment to discard");
        default:
          fail(node->getLoc(), "unsupported jump statement");
      }
    }
    if (glslang::TIntermSwitch* switch_node = node->getAsSwitchNode()) {
      statement.kind = StmtKind::Switch;
      statement.expression = lower_expr(switch_node->getCondition()->getAsTyped());
      for (TIntermNode* child : switch_node->getBody()->getSequence()) {
        if (child) lower_statement_into(child, statement.body);
      }
      return statement;
    }
    TIntermTyped* typed = node->getAsTyped();
    if (!typed) fail(node->getLoc(), "unsupported statement");
    statement.kind = StmtKind::Expression;
    statement.expression = lower_expr(typed);
    return statement;
  }

  Expr constant(const glslang::TConstUnionArray& values, const TType& type, const glslang::TSourceLoc& loc) {
    Expr expr;
    expr.kind = ExprKind::Constant;
    expr.type = lower_type(type, loc);
    expr.location = location(loc);
    for (int i = 0; i < values.size(); ++i) {
      const glslang::TConstUnion& value = values[i];
      switch (value.getType()) {
        case glslang::EbtFloat:
        case glslang::EbtDouble:
          expr.constant.push_back(value.getDConst());
          break;
        case glslang::EbtInt:
          expr.constant.push_back(value.getIConst());
          break;
        case glslang::EbtUint:
          expr.constant.push_back(value.getUConst());
          break;
        case glslang::EbtBool:
          expr.constant.push_back(value.getBConst() ? 1.0 : 0.0);
          break;
        default:
          fail(loc, "unsupported constant");
      }
    }
    return expr;
  }

  Expr node_of(ExprKind kind, TIntermTyped* typed) {
    Expr expr;
    expr.kind = kind;
    expr.type = lower_type(typed->getType(), typed->getLoc());
    expr.location = location(typed->getLoc());
    return expr;
  }

  Expr lower_expr(TIntermTyped* typed) {
    if (glslang::TIntermConstantUnion* value = typed->getAsConstantUnion()) {
      return constant(value->getConstArray(), value->getType(), value->getLoc());
    }
    if (glslang::TIntermSymbol* symbol = typed->getAsSymbolNode()) {
      if (symbol->getType().getQualifier().storage == glslang::EvqConst && symbol->getConstArray().size() > 0 &&
          variable_of_.count(symbol->getId()) == 0) {
        // A local const: glslang folded it everywhere but here.
        return constant(symbol->getConstArray(), symbol->getType(), symbol->getLoc());
      }
      Expr expr = node_of(ExprKind::Variable, typed);
      expr.variable = variable_of(symbol);
      return expr;
    }
    if (TIntermBinary* binary = typed->getAsBinaryNode()) return lower_binary(binary);
    if (TIntermUnary* unary = typed->getAsUnaryNode()) return lower_unary(unary);
    if (TIntermAggregate* aggregate = typed->getAsAggregate()) return lower_aggregate(aggregate);
    if (glslang::TIntermSelection* selection = typed->getAsSelectionNode()) {
      Expr expr = node_of(ExprKind::Select, typed);
      expr.operands.push_back(lower_expr(selection->getCondition()));
      expr.operands.push_back(lower_expr(selection->getTrueBlock()->getAsTyped()));
      expr.operands.push_back(lower_expr(selection->getFalseBlock()->getAsTyped()));
      return expr;
    }
    fail(typed->getLoc(), "unsupported expression");
  }

  Expr operation(TIntermTyped* typed, Operator op, std::initializer_list<TIntermTyped*> operands) {
    Expr expr = node_of(ExprKind::Operation, typed);
    expr.op = op;
    for (TIntermTyped* operand : operands) expr.operands.push_back(lower_expr(operand));
    return expr;
  }

  Expr builtin(TIntermTyped* typed, Builtin which, const std::vector<TIntermTyped*>& operands) {
    Expr expr = node_of(ExprKind::BuiltinCall, typed);
    expr.builtin = which;
    for (TIntermTyped* operand : operands) expr.operands.push_back(lower_expr(operand));
    return expr;
  }

  Expr assign(TIntermBinary* binary, bool compound, Operator op) {
    Expr expr = node_of(ExprKind::Assign, binary);
    expr.compound = compound;
    expr.op = op;
    expr.operands.push_back(lower_expr(binary->getLeft()));
    expr.operands.push_back(lower_expr(binary->getRight()));
    return expr;
  }

  Expr lower_binary(TIntermBinary* binary) {
    TIntermTyped* left = binary->getLeft();
    TIntermTyped* right = binary->getRight();
    const bool vector_result = binary->getType().isVector();
    switch (binary->getOp()) {
      case glslang::EOpAssign:
        return assign(binary, false, Operator::Add);
      case glslang::EOpAddAssign:
        return assign(binary, true, Operator::Add);
      case glslang::EOpSubAssign:
        return assign(binary, true, Operator::Subtract);
      case glslang::EOpMulAssign:
      case glslang::EOpVectorTimesScalarAssign:
      case glslang::EOpMatrixTimesScalarAssign:
        return assign(binary, true, Operator::Multiply);
      case glslang::EOpVectorTimesMatrixAssign:
        return assign(binary, true, Operator::VectorTimesMatrix);
      case glslang::EOpMatrixTimesMatrixAssign:
        return assign(binary, true, Operator::MatrixTimesMatrix);
      case glslang::EOpDivAssign:
        return assign(binary, true, Operator::Divide);
      case glslang::EOpModAssign:
        return assign(binary, true, Operator::Modulo);
      case glslang::EOpAndAssign:
        return assign(binary, true, Operator::BitwiseAnd);
      case glslang::EOpInclusiveOrAssign:
        return assign(binary, true, Operator::BitwiseOr);
      case glslang::EOpExclusiveOrAssign:
        return assign(binary, true, Operator::BitwiseXor);
      case glslang::EOpLeftShiftAssign:
        return assign(binary, true, Operator::ShiftLeft);
      case glslang::EOpRightShiftAssign:
        return assign(binary, true, Operator::ShiftRight);
      case glslang::EOpAdd:
        return operation(binary, Operator::Add, {left, right});
      case glslang::EOpSub:
        return operation(binary, Operator::Subtract, {left, right});
      case glslang::EOpMul:
        if (left->getType().isMatrix() && right->getType().isMatrix()) {
          return builtin(binary, Builtin::MatrixCompMult, {left, right});
        }
        return operation(binary, Operator::Multiply, {left, right});
      case glslang::EOpVectorTimesScalar:
      case glslang::EOpMatrixTimesScalar:
        return operation(binary, Operator::Multiply, {left, right});
      case glslang::EOpDiv:
        return operation(binary, Operator::Divide, {left, right});
      case glslang::EOpMod:
        return operation(binary, Operator::Modulo, {left, right});
      case glslang::EOpRightShift:
        return operation(binary, Operator::ShiftRight, {left, right});
      case glslang::EOpLeftShift:
        return operation(binary, Operator::ShiftLeft, {left, right});
      case glslang::EOpAnd:
        return operation(binary, Operator::BitwiseAnd, {left, right});
      case glslang::EOpInclusiveOr:
        return operation(binary, Operator::BitwiseOr, {left, right});
      case glslang::EOpExclusiveOr:
        return operation(binary, Operator::BitwiseXor, {left, right});
      case glslang::EOpVectorTimesMatrix:
        return operation(binary, Operator::VectorTimesMatrix, {left, right});
      case glslang::EOpMatrixTimesVector:
        return operation(binary, Operator::MatrixTimesVector, {left, right});
      case glslang::EOpMatrixTimesMatrix:
        return operation(binary, Operator::MatrixTimesMatrix, {left, right});
      case glslang::EOpEqual:
        return operation(binary, Operator::Equal, {left, right});
      case glslang::EOpNotEqual:
        return operation(binary, Operator::NotEqual, {left, right});
      case glslang::EOpVectorEqual:
        return builtin(binary, Builtin::Equal, {left, right});
      case glslang::EOpVectorNotEqual:
        return builtin(binary, Builtin::NotEqual, {left, right});
      case glslang::EOpLessThan:
        return vector_result ? builtin(binary, Builtin::LessThan, {left, right})
                             : operation(binary, Operator::Less, {left, right});
      case glslang::EOpGreaterThan:
        return vector_result ? builtin(binary, Builtin::GreaterThan, {left, right})
                             : operation(binary, Operator::Greater, {left, right});
      case glslang::EOpLessThanEqual:
        return vector_result ? builtin(binary, Builtin::LessThanEqual, {left, right})
                             : operation(binary, Operator::LessEqual, {left, right});
      case glslang::EOpGreaterThanEqual:
        return vector_result ? builtin(binary, Builtin::GreaterThanEqual, {left, right})
                             : operation(binary, Operator::GreaterEqual, {left, right});
      case glslang::EOpLogicalAnd:
        return operation(binary, Operator::LogicalAnd, {left, right});
      case glslang::EOpLogicalOr:
        return operation(binary, Operator::LogicalOr, {left, right});
      case glslang::EOpLogicalXor:
        return operation(binary, Operator::LogicalXor, {left, right});
      case glslang::EOpComma: {
        Expr expr = node_of(ExprKind::Comma, binary);
        expr.operands.push_back(lower_expr(left));
        expr.operands.push_back(lower_expr(right));
        return expr;
      }
      case glslang::EOpIndexDirect:
      case glslang::EOpIndexIndirect: {
        Expr expr = node_of(ExprKind::Index, binary);
        expr.operands.push_back(lower_expr(left));
        expr.operands.push_back(lower_expr(right));
        return expr;
      }
      case glslang::EOpIndexDirectStruct: {
        Expr expr = node_of(ExprKind::Member, binary);
        expr.operands.push_back(lower_expr(left));
        expr.member = right->getAsConstantUnion()->getConstArray()[0].getIConst();
        return expr;
      }
      case glslang::EOpVectorSwizzle: {
        Expr expr = node_of(ExprKind::Swizzle, binary);
        expr.operands.push_back(lower_expr(left));
        for (TIntermNode* component : right->getAsAggregate()->getSequence()) {
          expr.components.push_back(component->getAsConstantUnion()->getConstArray()[0].getIConst());
        }
        return expr;
      }
      default:
        fail(binary->getLoc(), fmt::format("unsupported operator ({})", static_cast<int>(binary->getOp())));
    }
  }

  Expr conversion(TIntermUnary* unary) {
    Expr expr = node_of(ExprKind::Construct, unary);
    expr.operands.push_back(lower_expr(unary->getOperand()));
    return expr;
  }

  [[noreturn]] void refuse_derivative(TIntermTyped* node, const char* name) {
    // glslang places a one-argument built-in's call inside its argument: the message points at the
    // name, its last use on the line before that place.
    const glslang::TSourceLoc& loc = node->getLoc();
    const std::string_view text = code_line(loc.line);
    const size_t at = text.rfind(name, static_cast<size_t>(std::max(loc.column - 1, 0)));
    glslang::TSourceLoc named = loc;
    if (at != std::string_view::npos) named.column = static_cast<int>(at) + 1;
    fail(named, fmt::format("'{}': derivatives cannot be used in a distance function (it is evaluated at "
                            "points, not over a pixel's neighbours)",
                            name));
  }

  Expr lower_unary(TIntermUnary* unary) {
    TIntermTyped* operand = unary->getOperand();
    const glslang::TOperator op = unary->getOp();
    if (op >= glslang::EOpConvInt8ToBool && op <= glslang::EOpConvDoubleToFloat) return conversion(unary);
    switch (op) {
      case glslang::EOpNegative:
        return operation(unary, Operator::Negate, {operand});
      case glslang::EOpLogicalNot:
        return operation(unary, Operator::LogicalNot, {operand});
      case glslang::EOpBitwiseNot:
        return operation(unary, Operator::BitwiseNot, {operand});
      case glslang::EOpPostIncrement:
        return operation(unary, Operator::PostIncrement, {operand});
      case glslang::EOpPostDecrement:
        return operation(unary, Operator::PostDecrement, {operand});
      case glslang::EOpPreIncrement:
        return operation(unary, Operator::PreIncrement, {operand});
      case glslang::EOpPreDecrement:
        return operation(unary, Operator::PreDecrement, {operand});
      case glslang::EOpDPdx:
      case glslang::EOpDPdxFine:
      case glslang::EOpDPdxCoarse:
        refuse_derivative(unary, "dFdx");
      case glslang::EOpDPdy:
      case glslang::EOpDPdyFine:
      case glslang::EOpDPdyCoarse:
        refuse_derivative(unary, "dFdy");
      case glslang::EOpFwidth:
      case glslang::EOpFwidthFine:
      case glslang::EOpFwidthCoarse:
        refuse_derivative(unary, "fwidth");
      default:
        break;
    }
    const std::optional<Builtin> which = builtin_of(op, unary);
    if (!which) fail(unary->getLoc(), fmt::format("unsupported built-in function ({})", static_cast<int>(op)));
    return builtin(unary, *which, {operand});
  }

  std::optional<Builtin> builtin_of(glslang::TOperator op, TIntermTyped* node) {
    switch (op) {
      case glslang::EOpRadians:
        return Builtin::Radians;
      case glslang::EOpDegrees:
        return Builtin::Degrees;
      case glslang::EOpSin:
        return Builtin::Sin;
      case glslang::EOpCos:
        return Builtin::Cos;
      case glslang::EOpTan:
        return Builtin::Tan;
      case glslang::EOpAsin:
        return Builtin::Asin;
      case glslang::EOpAcos:
        return Builtin::Acos;
      case glslang::EOpAtan:
        return node->getAsAggregate() ? Builtin::Atan2 : Builtin::Atan;
      case glslang::EOpSinh:
        return Builtin::Sinh;
      case glslang::EOpCosh:
        return Builtin::Cosh;
      case glslang::EOpTanh:
        return Builtin::Tanh;
      case glslang::EOpAsinh:
        return Builtin::Asinh;
      case glslang::EOpAcosh:
        return Builtin::Acosh;
      case glslang::EOpAtanh:
        return Builtin::Atanh;
      case glslang::EOpPow:
        return Builtin::Pow;
      case glslang::EOpExp:
        return Builtin::Exp;
      case glslang::EOpLog:
        return Builtin::Log;
      case glslang::EOpExp2:
        return Builtin::Exp2;
      case glslang::EOpLog2:
        return Builtin::Log2;
      case glslang::EOpSqrt:
        return Builtin::Sqrt;
      case glslang::EOpInverseSqrt:
        return Builtin::InverseSqrt;
      case glslang::EOpAbs:
        return Builtin::Abs;
      case glslang::EOpSign:
        return Builtin::Sign;
      case glslang::EOpFloor:
        return Builtin::Floor;
      case glslang::EOpTrunc:
        return Builtin::Trunc;
      case glslang::EOpRound:
        return Builtin::Round;
      case glslang::EOpRoundEven:
        return Builtin::RoundEven;
      case glslang::EOpCeil:
        return Builtin::Ceil;
      case glslang::EOpFract:
        return Builtin::Fract;
      case glslang::EOpMod:
        return Builtin::Mod;
      case glslang::EOpModf:
        return Builtin::Modf;
      case glslang::EOpMin:
        return Builtin::Min;
      case glslang::EOpMax:
        return Builtin::Max;
      case glslang::EOpClamp:
        return Builtin::Clamp;
      case glslang::EOpMix:
        return Builtin::Mix;
      case glslang::EOpStep:
        return Builtin::Step;
      case glslang::EOpSmoothStep:
        return Builtin::SmoothStep;
      case glslang::EOpIsNan:
        return Builtin::IsNan;
      case glslang::EOpIsInf:
        return Builtin::IsInf;
      case glslang::EOpFloatBitsToInt:
        return Builtin::FloatBitsToInt;
      case glslang::EOpFloatBitsToUint:
        return Builtin::FloatBitsToUint;
      case glslang::EOpIntBitsToFloat:
        return Builtin::IntBitsToFloat;
      case glslang::EOpUintBitsToFloat:
        return Builtin::UintBitsToFloat;
      case glslang::EOpLength:
        return Builtin::Length;
      case glslang::EOpDistance:
        return Builtin::Distance;
      case glslang::EOpDot:
        return Builtin::Dot;
      case glslang::EOpCross:
        return Builtin::Cross;
      case glslang::EOpNormalize:
        return Builtin::Normalize;
      case glslang::EOpFaceForward:
        return Builtin::FaceForward;
      case glslang::EOpReflect:
        return Builtin::Reflect;
      case glslang::EOpRefract:
        return Builtin::Refract;
      case glslang::EOpOuterProduct:
        return Builtin::OuterProduct;
      case glslang::EOpTranspose:
        return Builtin::Transpose;
      case glslang::EOpDeterminant:
        return Builtin::Determinant;
      case glslang::EOpMatrixInverse:
        return Builtin::Inverse;
      case glslang::EOpVectorEqual:
        return Builtin::Equal;
      case glslang::EOpVectorNotEqual:
        return Builtin::NotEqual;
      case glslang::EOpLessThan:
        return Builtin::LessThan;
      case glslang::EOpLessThanEqual:
        return Builtin::LessThanEqual;
      case glslang::EOpGreaterThan:
        return Builtin::GreaterThan;
      case glslang::EOpGreaterThanEqual:
        return Builtin::GreaterThanEqual;
      case glslang::EOpAny:
        return Builtin::Any;
      case glslang::EOpAll:
        return Builtin::All;
      case glslang::EOpVectorLogicalNot:
        return Builtin::Not;
      default:
        return std::nullopt;
    }
  }

  Expr lower_aggregate(TIntermAggregate* aggregate) {
    const glslang::TOperator op = aggregate->getOp();
    std::vector<TIntermTyped*> operands;
    for (TIntermNode* child : aggregate->getSequence()) operands.push_back(child->getAsTyped());
    if (op == glslang::EOpFunctionCall) {
      const auto found = definition_of_.find(aggregate->getName().c_str());
      if (found == definition_of_.end() || !function_index_) fail(aggregate->getLoc(), "call of an undefined function");
      Expr expr = node_of(ExprKind::Call, aggregate);
      expr.function = function_index_->at(found->second);
      for (TIntermTyped* operand : operands) expr.operands.push_back(lower_expr(operand));
      return expr;
    }
    if (op == glslang::EOpComma) {
      Expr expr = node_of(ExprKind::Comma, aggregate);
      for (TIntermTyped* operand : operands) expr.operands.push_back(lower_expr(operand));
      return expr;
    }
    if (aggregate->isConstructor()) {
      Expr expr = node_of(ExprKind::Construct, aggregate);
      for (TIntermTyped* operand : operands) expr.operands.push_back(lower_expr(operand));
      return expr;
    }
    if (aggregate->isTexture() || aggregate->isSampling() || aggregate->isImage()) {
      fail(aggregate->getLoc(), "texture lookups cannot be used in a distance function: it has no texture units");
    }
    if (op == glslang::EOpMul) return builtin(aggregate, Builtin::MatrixCompMult, operands);
    const std::optional<Builtin> which = builtin_of(op, aggregate);
    if (!which) fail(aggregate->getLoc(), fmt::format("unsupported built-in function ({})", static_cast<int>(op)));
    return builtin(aggregate, *which, operands);
  }

  const Source& source_;
  Module& module_;
  std::vector<Definition> definitions_;
  std::map<std::string, int> definition_of_;
  std::map<long long, int> variable_of_;
  std::map<const glslang::TTypeList*, int> struct_of_;
  const std::map<int, int>* function_index_ = nullptr;
  std::vector<int>* locals_ = nullptr;
};

std::string defines_text(const Source& source) {
  std::string text;
  for (const auto& [name, value] : source.defines) text += fmt::format("#define {} {}\n", name, value);
  return text;
}

}  // namespace

Module compile(const Source& source) {
  initialize_glslang_once();
  if (source.code.find("#version") != std::string::npos) {
    const size_t at = source.code.find("#version");
    const int line =
        source.first_line + static_cast<int>(std::count(source.code.begin(), source.code.begin() + at, '\n'));
    throw InputError(
        fmt::format("{}:{}: remove #version: clmarch reads the code as GLSL ES 3.00 (#version 300 es), "
                    "as WebGL 2 and Shadertoy do",
                    source.file_name, line));
  }
  const std::string prelude = std::string(kPrelude) + defines_text(source);
  // #line makes glslang count the user's lines from the scene file's line of inline code.
  const std::string code = fmt::format("#line {}\n{}\n", source.first_line, source.code);
  const char* strings[] = {prelude.c_str(), code.c_str()};
  const char* names[] = {"<clmarch prelude>", source.file_name.c_str()};
  glslang::TShader shader(EShLangFragment);
  shader.setStringsWithLengthsAndNames(strings, nullptr, names, 2);
  const EShMessages messages = static_cast<EShMessages>(EShMsgKeepUncalled);
  if (!shader.parse(GetDefaultResources(), 300, EEsProfile, false, false, messages)) {
    throw InputError(first_error(shader.getInfoLog(), source));
  }
  Module module;
  module.file_name = source.file_name;
  Lowering(source, module).run(shader.getIntermediate()->getTreeRoot());
  return module;
}

}  // namespace clmarch::glsl
