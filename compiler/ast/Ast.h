#pragma once
// The syntax tree of a .gbx file. Statements share one node type because the grammar
// is uniform (every block holds statements); which statement may stand where is a
// question for sema, which answers it with a diagnostic.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "source/Source.h"

namespace gbx::ast {

using source::Span;

// One factor of a unit expression: `mm` with exponent -1 in `N/(mm*um)`.
struct UnitFactor {
  std::string atom;
  int exponent = 1;
  Span span;
};

struct UnitExpr {
  std::vector<UnitFactor> factors;
  std::string text;  // as written, for messages
  Span span;
};

enum class ExprKind {
  Number,     // text = literal; unit optional
  Name,       // text = identifier
  String,     // text = contents
  Bool,       // boolValue
  Neg,        // args[0]
  Not,        // args[0]
  Binary,     // binOp; args[0], args[1]
  Compare,    // cmpOp; args[0], args[1]
  Tolerance,  // args[0] +- args[1]
  InRange,    // args[0] in args[1]..args[2]
  InSet,      // args[0] in args[1] (a Set)
  Set,        // args
  Call,       // args[0] callee, args[1..] arguments
  Member,     // args[0].text
  Forall,     // forall text in args[0]: args[1]
};

enum class BinOp { Add, Sub, Mul, Div, Pow, And, Or };
enum class CmpOp { Eq, Ne, Lt, Le, Gt, Ge };

const char* binOpText(BinOp op);
const char* cmpOpText(CmpOp op);

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

struct Expr {
  ExprKind kind = ExprKind::Number;
  Span span;
  std::string text;
  std::optional<UnitExpr> unit;
  BinOp binOp = BinOp::Add;
  CmpOp cmpOp = CmpOp::Eq;
  bool boolValue = false;
  std::vector<ExprPtr> args;

  ExprPtr clone() const;
};

struct Path {
  std::vector<std::string> parts;
  std::vector<Span> spans;  // one per part
  Span span;
  std::string str() const;
  bool empty() const { return parts.empty(); }
};

enum class StmtKind {
  Import, Const, Preset, Gearbox, Named,  // file level (Named: `material X { }` and strays)
  Stage, Like, Let, Require, Interchangeable, Minimize, Maximize, Operating, Scene, Effects,
  Modify, Split, Study, Report, Output, Sweep, Of, Top, Sort, Columns, Assign, Domain,
  Scatter,  // `main.face_width +- 1 mm;` in `tolerances`
  Bin,      // `bin 130% torque for 0.1% of life;` in `load_spectrum`: value, word, step, base
  Member,   // `shaft input { … }` in a gearbox: word `shaft`, name
  Segment,  // `segment 0 mm .. 60 mm { … }` in a shaft: lo, hi, body
  Placed,   // `WORD [path] at POSITION ({ … } | ;)` in a shaft: word, path (gear or name), value, body
  Block, Flag,
};

const char* stmtKindName(StmtKind k);

enum class DomainKind { Range, Set, Named };

struct Stmt {
  StmtKind kind = StmtKind::Flag;
  Span span;
  std::string name;  // declared or block name
  Span nameSpan;
  std::string word;  // stage kind, preset target, `material`, `of` word, import target
  Span wordSpan;
  bool importIsPath = false;
  bool sceneRef = false;  // `x = scene NAME;`: value is the scene's name
  bool cycles = false;    // a bin's duration in load cycles (`for 1e7 cycles`), not a share of the life
  std::vector<std::string> with;  // presets applied to a stage
  std::vector<Span> withSpans;
  std::string base;  // `extends` gearbox
  Span baseSpan;
  Path path;         // assignment/domain target, scene/modify target, like source
  ExprPtr value, when, lo, hi, step;
  DomainKind domain = DomainKind::Range;
  std::vector<ExprPtr> exprs;  // set members, outputs, columns
  std::vector<Path> paths;     // interchangeable
  std::vector<Stmt> body;
  bool hasBody = false;

  Stmt clone() const;
};

struct File {
  int fileId = -1;
  std::vector<Stmt> decls;
};

// `dump ast`: an indented, stable rendering.
std::string print(const File& f);
std::string print(const Expr& e);

} // namespace gbx::ast
