#pragma once
// Checks an expression in a scope and turns it into a typed IR expression: names
// resolved to quantity paths, units to SI, dimensions checked, constants folded.
// Every failure is a diagnostic and an Error-typed node, never an exception.
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "catalogue/Functions.h"
#include "diag/Diagnostic.h"
#include "ir/Ir.h"
#include "sema/Model.h"

namespace gbx::sema {

// A typed node of the checked tree.
ir::ExprPtr make(ir::Op op, ir::Type t, source::Span span, std::string name = {});

struct Scope {
  enum Context { General, Modify, EffectParam, ConstExpr };
  const GearboxModel* gearbox = nullptr;
  const StageModel* stage = nullptr;  // names resolve to this stage first
  Context context = General;
  std::string modifyGear;                  // "pinion" in a rule targeting one gear
  std::vector<std::string> effectLocals;   // `stiffness` inside hertz_contact
  bool hasBaseline = false;                // `relative(x)` allowed
  bool hasTolerances = false;              // `worst(q)` and `mean(q)` over `tolerances` allowed
  bool hasSamples = false;                 // `quantile(q, p)` too: the tolerances are sampled
  bool meshPeriodsAllowed = false;
};

class ExprChecker {
public:
  ExprChecker(const Globals& g, diag::DiagnosticEngine& diags) : globals_(g), diags_(diags) {}

  ir::ExprPtr check(const ast::Expr* e, const Scope& scope);
  // A range `lo..hi`: a bare number on the left takes the unit written on the right.
  std::pair<ir::ExprPtr, ir::ExprPtr> checkRange(const ast::Expr* lo, const ast::Expr* hi, const Scope& scope);
  // Converts a literal with its unit to SI; reports unknown units.
  // `difference`: the literal is a difference (a sweep's step), so a unit's zero (`degC`) is
  // not added.
  ir::ExprPtr literal(const ast::Expr& e, const ast::UnitExpr* unitOverride = nullptr, bool difference = false);
  // `20 degC`: a literal on a scale whose zero is not SI's (a Celsius temperature). Such a
  // value can be compared and subtracted, not added, scaled or used as a tolerance or step.
  static bool celsiusLiteral(const ast::Expr* e);
  // `what` (a tolerance, a step) is a difference: a Celsius literal there is E0302, naming the
  // K to write; true when it was refused.
  bool refuseCelsiusDifference(const ast::Expr* e, const char* what);

  // Resolves a `let` lazily, so lets may refer to each other in any order.
  void setLetResolver(std::function<ir::Type(const std::string& gearboxLet, const StageModel* stage)> f) {
    letResolver_ = std::move(f);
  }

private:
  struct Bound {
    std::string name;
    ir::ExprPtr value;         // a Quantity for `z in teeth`
    const StageModel* stage = nullptr;  // for `s in stages`
  };

  ir::ExprPtr error(const source::Span& span);
  ir::ExprPtr name(const ast::Expr& e, const Scope& s);
  ir::ExprPtr member(const ast::Expr& e, const Scope& s);
  ir::ExprPtr call(const ast::Expr& e, const Scope& s);
  // `scene.fn(signal)`: a result of a scene.
  ir::ExprPtr sceneResult(const ast::Expr& e, const ast::Expr& callee, const std::vector<const ast::Expr*>& argAst, const Scope& s);
  // The arguments of a catalogue function against its row's rule: the node itself where the
  // rule makes it (relative, worst, a per-gear reduction) or an error node; nullptr when a
  // plain call follows.
  ir::ExprPtr argumentsByRule(const cat::FunctionSpec& spec, std::vector<ir::ExprPtr>& args, const ast::Expr& e, const Scope& s);
  ir::ExprPtr scatterCall(const cat::FunctionSpec& spec, std::vector<ir::ExprPtr>& args, const ast::Expr& e, const Scope& s);
  // The result's type from the row's rule; false (reported) where it has none.
  bool resultType(const cat::FunctionSpec& spec, const std::vector<ir::ExprPtr>& args, ir::Type& t);
  ir::ExprPtr binary(const ast::Expr& e, const Scope& s);
  ir::ExprPtr compare(const ast::Expr& e, const Scope& s);
  ir::ExprPtr tolerance(const ast::Expr& e, const Scope& s);
  ir::ExprPtr forall(const ast::Expr& e, const Scope& s);
  ir::ExprPtr stageMember(const StageModel& st, const std::string& m, const source::Span& span);
  ir::ExprPtr quantity(const std::string& path, const AttrSpec& spec, const source::Span& span);
  // ExprShafts.cpp: a shaft's, a bearing's and a notch's results.
  ir::ExprPtr shaftMember(const std::string& shaft, const std::string& m, const source::Span& span, const Scope& s);
  ir::ExprPtr bearingMember(const std::string& bearing, const std::string& m, const source::Span& span);
  ir::ExprPtr notchMember(const std::string& notch, const std::string& m, const source::Span& span);
  ir::ExprPtr notchAt(const ast::Expr& e, const ir::Expr& obj, const std::vector<const ast::Expr*>& argAst,
                      const Scope& s);
  ir::ExprPtr shaftAt(const ast::Expr& e, const ast::Expr& callee, const ir::Expr& obj, const std::vector<const ast::Expr*>& argAst,
                      const Scope& s);
  ir::ExprPtr requireNumber(ir::ExprPtr x, const char* what);
  bool requireBool(const ir::Expr& x, const char* what);
  std::vector<std::string> visibleNames(const Scope& s) const;

  const Globals& globals_;
  diag::DiagnosticEngine& diags_;
  std::vector<Bound> bound_;
  std::function<ir::Type(const std::string&, const StageModel*)> letResolver_;
};

// "a length (mm)": the dimension's name and, when given, the unit as written.
std::string describe(const ir::Type& t, const std::string& written = "");

} // namespace gbx::sema
