#pragma once
// A gearbox as sema sees it after `extends`, presets and `like` are applied: every
// member points at the AST statement that declared it, with where it came from.
#include <map>
#include <string>
#include <vector>

#include "ast/Ast.h"
#include "ir/Ir.h"
#include "sema/Catalogue.h"

namespace gbx::sema {

struct Binding {
  const ast::Stmt* stmt = nullptr;  // an Assign or a Domain
  std::string origin;               // "stage", "preset klingelnberg", "like upper", "gearbox X"
};

struct ScopedStmt {
  const ast::Stmt* stmt = nullptr;
  std::string scope;  // stage name for statements written inside a stage, else ""
};

struct StageModel {
  std::string name;
  const KindSpec* kind = nullptr;  // null when the kind is unknown (already reported)
  const ast::Stmt* decl = nullptr;
  std::vector<std::string> presets;
  std::string likeOf;
  bool likePending = false;  // `stage b like a;` not yet copied from `a`
  std::vector<std::pair<std::string, Binding>> attrs;  // in declaration order
  std::vector<ScopedStmt> rules;                       // `require` inside the stage
  std::vector<const ast::Stmt*> lets;                  // `let` inside the stage
  bool rated = false;                                  // has a `rating { … }` block
  const ast::Stmt* spectrum = nullptr;                 // its `load_spectrum { … }`

  Binding* findAttr(const std::string& path);
  const Binding* findAttr(const std::string& path) const;
  void setAttr(const std::string& path, Binding b);
};

struct GearboxModel {
  std::string name;
  std::string base;
  const ast::Stmt* decl = nullptr;
  std::vector<StageModel> stages;
  std::vector<ScopedStmt> rules;
  std::vector<const ast::Stmt*> lets;
  std::vector<const ast::Stmt*> interchangeables;
  std::vector<const ast::Stmt*> objectives;
  std::vector<std::pair<std::string, Binding>> operating;
  bool hasOperating = false;
  std::vector<const ast::Stmt*> scenes;
  std::vector<const ast::Stmt*> modifies;
  std::vector<const ast::Stmt*> splits;
  std::vector<const ast::Stmt*> shafts;
  std::map<std::string, std::vector<std::pair<std::string, Binding>>> splitOverrides;
  std::vector<const ast::Stmt*> studies;
  std::vector<const ast::Stmt*> tolerances;  // the lines of `tolerances { … }`, a variant's replacing by target
  std::vector<const ast::Stmt*> toleranceSettings;  // its `samples = N;` and the like, replaced by name
  const ast::Stmt* report = nullptr;

  const StageModel* findStage(const std::string& n) const;
  StageModel* findStage(const std::string& n);
  const ast::Stmt* findScene(const std::string& n) const;
  const ast::Stmt* findSplit(const std::string& n) const;
  const ast::Stmt* findShaft(const std::string& n) const;
  const ast::Stmt* findLet(const std::string& n) const;
};

// Names visible in every gearbox.
struct Globals {
  std::map<std::string, const ast::Stmt*> consts, materials, presets, gearboxes;
  std::map<std::string, ir::ExprPtr> constValues;
};

} // namespace gbx::sema
