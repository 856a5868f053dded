#pragma once
// The checker of a loaded program (sema::analyse): its state and its steps. The steps live
// in one file per topic: declarations and settings (Sema.cpp), stages and attributes
// (SemaStages.cpp), ratings and their inputs (SemaRatings.cpp), rules, tolerances and
// objectives (SemaRules.cpp), a gearbox lowered to the IR (SemaGearbox.cpp), scenes,
// modifications and splits (SemaScenes.cpp), studies and the report (SemaStudies.cpp).
// Only those files include this header.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "catalogue/Budgets.h"
#include "sema/Catalogue.h"
#include "sema/ExprChecker.h"
#include "sema/Model.h"
#include "sema/Sema.h"
#include "units/Unit.h"

namespace gbx::sema {

using ast::Stmt;
using ast::StmtKind;
using ir::Op;
using ir::Type;
using source::Span;
using units::Number;

inline constexpr std::string_view kRatingBlock = "rating";
// A rating's load spectrum and the words of its bins (`bin 130% torque for 0.1% of life;`).
inline constexpr std::string_view kSpectrumBlock = "load_spectrum", kBinWord = "bin", kTorqueWord = "torque", kLifeWord = "life";

inline Span nameOr(const Stmt& s) { return s.nameSpan.valid() ? s.nameSpan : s.span; }

inline void walk(const ir::Expr& e, const std::function<void(const ir::Expr&)>& f) {
  f(e);
  for (const auto& a : e.args)
    if (a) walk(*a, f);
}

inline std::string lastPart(const std::string& p) {
  auto d = p.rfind('.');
  return d == std::string::npos ? p : p.substr(d + 1);
}

// Whether a written name is the catalogue's name of `key` (names are compared through the
// catalogue, never as literals).
inline bool isKey(std::string_view name, Q key) { return keyOf(name) == key; }

// Whether a scene output reads `signal`.
inline bool isSignal(const ir::SceneOutput& o, cat::Signal signal) {
  const auto* s = cat::findSignal(o.signal);
  return s && s->id == signal;
}

inline bool needsOperating(const std::string& path) {
  auto key = keyOf(lastPart(path));
  return key && dependsOnOperatingPoint(*key);
}

class Analyser {
public:
  Analyser(diag::DiagnosticEngine& d) : diags_(d), checker_(globals_, d) {}

  ir::Program run(const LoadedProgram& prog);

private:
  // ---- Sema.cpp: declarations, constants, materials, presets, settings --------------------------
  void declare(std::map<std::string, const Stmt*>& table, const Stmt& d);
  void collect(const LoadedProgram& prog);
  void checkConsts();
  // `skip`: blocks the caller reads itself (a rating's `load_spectrum`).
  void flatten(const std::vector<Stmt>& body, const std::string& prefix, const std::string& owner,
               std::vector<std::pair<std::string, Binding>>& out, const std::set<std::string>& blocks,
               const std::set<std::string>& skip = {});
  void notAllowed(const Stmt& st, const std::string& owner);
  ir::Setting setting(const std::string& name, const Binding& b, const AttrSpec& spec, const Scope& scope,
                      const std::string& owner);
  std::optional<int> orderArgument(const cat::SignalFnSpec& fn, const ast::Expr* k, Span span,
                                   const std::string& signal);
  static ir::Setting switchSetting(ir::Setting out, bool on);
  bool sweptValueFits(const AttrSpec& spec, const std::string& target, const ir::Expr& x);
  void seriesOf(const Stmt& b, const GearboxModel& m, const Scope& gs, const std::string& owner, ir::Study& out);
  ir::Setting listSetting(ir::Setting out, const ast::Expr* v, const AttrSpec& spec, const Scope& scope);
  ir::Setting domainSetting(ir::Setting out, const Stmt& st, const AttrSpec& spec, const Scope& scope,
                            const std::string& owner);
  std::vector<ir::Setting> settings(const std::vector<std::pair<std::string, Binding>>& items,
                                    const std::vector<AttrSpec>& specs, const Scope& scope, const std::string& owner,
                                    Span ownerSpan, const char* missingCode);
  ir::Material material(const Stmt& d);
  void checkPreset(const Stmt& d);
  void unknownKind(const std::string& word, Span span);

  // ---- SemaStages.cpp: gearbox models (extends, presets, like), stages and attributes -----------
  StageModel makeStage(const Stmt& st);
  static std::string asWritten(const ast::Expr* v, const ir::Expr& x);
  bool outsideLimits(const AttrSpec& spec, const std::string& name, const ir::Expr& x, const ast::Expr* v);
  void dupInBlock(std::map<std::string, const Stmt*>& seen, const Stmt& st, const char* what);
  const GearboxModel* build(const std::string& name, std::vector<std::string>& stack);
  std::vector<const Stmt*> stagesOf(GearboxModel& model, const Stmt& decl, std::map<std::string, const Stmt*>& seen);
  void resolveLike(GearboxModel& model, const Stmt& st, const std::vector<const Stmt*>& likes, std::set<std::string>& resolving,
                   const std::string& name);
  void statementsOf(GearboxModel& model, const Stmt& decl, std::map<std::string, const Stmt*>& seen, const std::string& name,
                    const std::string& origin);
  void override(GearboxModel& m, const Stmt& st, const std::string& origin);
  void unknownAttribute(const StageModel& st, const std::string& path, Span where);
  std::optional<Number> boundOf(const AttrSpec& spec, const std::string& path, bool tooth, ir::ExprPtr x);
  struct Domain {
    std::optional<Number> lo, hi;
    std::vector<Number> members;
    std::vector<std::string> memberTexts; // as written, when every member is a literal
  };
  Domain domain(const AttrSpec& spec, const std::string& path, const Stmt& s, const Scope& scope, bool tooth = false);
  ir::Attribute attribute(const StageModel& st, const std::string& path, const Binding& b, const Scope& scope);
  void bevelGear(const Stmt& s, const GearboxModel& m, const Scope& gs, const std::string& owner, ir::Shaft::Placed& p);
  void noStageToSearch(const ir::Shaft& out, const GearboxModel& m, const std::string& owner);
  ir::Stage stage(const StageModel& st, const Scope& gbScope);
  template <class T, class Key>
  static void replaceOrAdd(std::vector<T>& v, T item, Key key) {
    for (auto& x : v)
      if (key(x) == key(item)) {
        x = std::move(item);
        return;
      }
    v.push_back(std::move(item));
  }

  // ---- SemaRatings.cpp: ratings and what they need ----------------------------------------------
  void ratingBlock(StageModel& m, const Stmt& b, std::map<std::string, const Stmt*>& seen);
  void gearBlock(StageModel& m, const Stmt& b, std::map<std::string, const Stmt*>& seen);
  void stageItems(StageModel& m, std::vector<std::pair<std::string, Binding>>& items,
                  std::map<std::string, const Stmt*>& seen);
  void ratingInputs(const StageModel& st, Span where, bool bearingsReadOil = false);
  void bevelRatingInputs(const StageModel& st, Span where);
  static bool rateable(const cat::KindSpec& kind);
  bool misspeltIn(const StageModel& st, const std::string& need) const;
  void requireMaterial(const ir::Gearbox& g, const GearboxModel& m);
  void requireRating(const ir::Gearbox& g, const GearboxModel& m);
  void thicknessAllowances(const ir::Gearbox& g, const GearboxModel& m);
  void sceneFactors(const ir::Gearbox& g);
  void planetaryGears(const ir::Gearbox& g);
  void ringRim(const ir::Stage& st);
  void planetBearingInputs(const StageModel& st, const ir::Expr& x, Q k, const char* where,
                           std::set<std::pair<int, int>>& reported);
  std::vector<ir::SpectrumBin> spectrumBins(const StageModel& st);
  void requireOperating(const ir::Gearbox& g);
  void checkOperating(const GearboxModel& m, const std::vector<ir::Setting>& op, const Stmt* decl);

  // ---- SemaRules.cpp: rules, `worst`, tolerances, objectives ------------------------------------
  ir::Rule rule(const Stmt& st, const Scope& s, const std::string& scopeName);
  bool readsWorst(const ir::Expr& e, int depth = 0) const;
  void worstSense(ir::Expr& e, int sense, bool condition = false, bool negated = false);
  std::vector<ir::Tolerance> tolerances(const GearboxModel& m, const Scope& gs);
  // The block's settings; `misspelt`: it names one it does not take (E0214 said so).
  struct ToleranceSettings {
    std::vector<ir::Setting> settings;
    bool misspelt = false;
  };
  ToleranceSettings toleranceSettings(const GearboxModel& m, const Scope& gs);
  void selfDefined(const ir::Gearbox& g);
  ir::Objective objective(const Stmt& st, const Scope& gs);

  // ---- SemaGearbox.cpp: a gearbox lowered to the IR ---------------------------------------------
  static void mergeModify(std::vector<ir::Modify>& modifies, ir::Modify built);
  ir::Gearbox lowerGearbox(const GearboxModel& m);

  // ---- SemaScenes.cpp: scenes, modifications, splits --------------------------------------------
  std::vector<std::string> interchangeable(const Stmt& st, const GearboxModel& m);
  ir::Scene scene(const Stmt& st, const GearboxModel& m, const Scope& gs);
  void flattenOne(const Stmt& b, std::vector<std::pair<std::string, Binding>>& items, const std::string& owner);
  void effects(const Stmt& block, ir::Scene& out, const Scope& gs);
  static std::string dotted(const ast::Expr* e);
  static std::vector<std::string> meshNames(const StageModel& st);
  void sceneOutput(const ast::Expr* e, ir::Scene& out, const StageModel* stage, const GearboxModel& m, bool whole);
  bool beyondBudget(const AttrSpec& spec, const std::string& name, const ir::Expr& x);
  void sceneBudgets(const ir::Scene& sc, const std::string& owner);
  void steadyStateRules(const ir::Scene& out, const Stmt& st, const std::string& owner);
  ir::Modify modify(const Stmt& st, const GearboxModel& m, const Scope& gs);
  void missingInputs(const StageModel& stage, const ir::ModRule& r, const Stmt& b);
  ir::Split split(const Stmt& st, const GearboxModel& m, const Scope& gs);
  ir::Shaft shaft(const Stmt& st, const GearboxModel& m, const Scope& gs);
  void notchGeometry(const ir::Shaft& sh, const std::string& owner);
  void notchNeeds(const ir::Shaft::Placed& p, const std::string& what, const Span& at);
  std::optional<ir::Shaft::Placed> placed(const Stmt& s, const GearboxModel& m, const Scope& gs, const std::string& owner,
                                          std::set<std::string>& bearings);
  std::optional<Number> position(const ast::Expr* e, const Scope& gs, const std::string& what);

  // ---- SemaStudies.cpp: studies and the report --------------------------------------------------
  ir::Study study(const Stmt& st, const GearboxModel& m, const Scope& gs);
  void sweepOf(const Stmt& b, const GearboxModel& m, const Scope& gs, const std::string& owner, ir::Study& out);
  void checkContinuation(const ir::Study& out, const std::string& owner);
  void checkRuns(const ir::Study& out, const Stmt& st, const std::string& owner);
  ir::Setting domainSetting(const Stmt& b, const AttrSpec& spec, const Scope& gs);
  std::optional<units::Dim> sweepTarget(const ast::Path& p, const GearboxModel& m, const AttrSpec** spec = nullptr);
  ir::Report report(const Stmt& st, const Scope& gs);

  // ---- state ---------------------------------------------------------------------------------------
  const std::map<std::string, ir::ExprPtr>* lets_ = nullptr;  // the lets being built, by key
  std::map<std::string, int> letSense_;  // the direction each let reading `worst` was used in (0: both)
  std::set<std::pair<std::string, std::string>> misspelt_;  // (stage, attribute) a reported misspelling meant
  diag::DiagnosticEngine& diags_;
  // Within a shaft: its numeric settings may be ranges and sets (searched like attributes).
  bool shaftDomains_ = false;
  Globals globals_;
  ExprChecker checker_;
  std::map<std::string, std::unique_ptr<GearboxModel>> models_;
};

} // namespace gbx::sema
