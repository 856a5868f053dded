// The .gbx language, v1 (docs/language.md). The statement grammar is deliberately uniform:
// which statement may stand in which block is checked by the AST builder, so that a
// misplaced statement gets a sentence of its own instead of a bare syntax error.
grammar Gbx;

@parser::members {
  // Unit expressions are written without blanks (`N*m`, `kg/m^3`): `*`, `/` and `^`
  // continue a unit only when they touch both neighbours, so `22% * whole_depth` is a
  // percentage times a quantity, not the unit `%*whole_depth`.
  bool glued() {
    auto prev = _input->LT(-1);
    auto op = _input->LT(1);
    auto next = _input->LT(2);
    return prev && op && next && op->getStartIndex() == prev->getStopIndex() + 1 &&
           next->getStartIndex() == op->getStopIndex() + 1;
  }
  // A word that opens a statement only where it stands first (`bin` in a load spectrum),
  // without being reserved elsewhere.
  bool isWord(const char* w) {
    auto t = _input->LT(1);
    return t && t->getText() == w;
  }
  // `WORD [path] at …`: a placement in a shaft, told apart before it is parsed so that a
  // misspelt statement word (`minimise x;`) keeps its own message.
  bool placed() {
    size_t i = 2;
    while (_input->LT(static_cast<ssize_t>(i))->getType() == ID) {
      ++i;
      if (_input->LT(static_cast<ssize_t>(i))->getText() != ".") break;
      ++i;
    }
    return _input->LT(static_cast<ssize_t>(i))->getType() == AT;
  }
  // A unit stands on the number's line: `41` at the end of a line is never `41 normal_module`.
  bool sameLine() {
    auto prev = _input->LT(-1);
    auto next = _input->LT(1);
    return prev && next && prev->getLine() == next->getLine();
  }
}

file : topDecl* EOF ;

topDecl
  : IMPORT (ID | STRING) ';'                       # importDecl
  | CONST ID '=' expr ';'                          # constDecl
  | PRESET ID FOR ID block                         # presetDecl
  | GEARBOX ID (EXTENDS ID)? block                 # gearboxDecl
  | ID ID block                                    # namedDecl   // `material NAME { … }`
  ;

block : '{' stmt* '}' ;

stmt
  : STAGE ID ':' ID (WITH ID (',' ID)*)? block     # stageStmt
  | STAGE ID LIKE path ';'                         # likeStmt
  | LET ID '=' expr ';'                            # letStmt
  | REQUIRE expr ';'                               # requireStmt
  | INTERCHANGEABLE path (',' path)+ ';'           # interchangeableStmt
  | (MINIMIZE | MAXIMIZE) expr ';'                 # objectiveStmt
  | OPERATING block                                # operatingStmt
  | SCENE ID ON path block                         # sceneStmt
  | EFFECTS block                                  # effectsStmt
  | MODIFY path block                              # modifyStmt
  | SPLIT ID block                                 # splitStmt
  | STUDY ID block                                 # studyStmt
  | REPORT block                                   # reportStmt
  | OUTPUT expr (',' expr)* ';'                    # outputStmt
  | SWEEP path IN tolExpr '..' tolExpr STEP tolExpr ';' # sweepStmt
  | ID OF path ';'                                 # ofStmt
  | TOP expr ';'                                   # topStmt
  | SORT BY expr ';'                               # sortStmt
  | COLUMNS expr (',' expr)* ';'                   # columnsStmt
  | path '=' (SCENE ID | expr) (WHEN expr)? ';'    # assignStmt  // also `dynamic_factor = scene vib;`
  | path IN domain ';'                             # domainStmt
  | path PLUSMINUS addExpr ';'                     # scatterStmt  // in `tolerances`
  | {isWord("bin")}? ID tolExpr ID? FOR tolExpr (OF ID)? ';' # binStmt  // `bin 130% torque for 0.1% of life;`
  | {isWord("segment")}? ID tolExpr '..' tolExpr block        # segmentStmt  // `segment 0 mm .. 60 mm { … }`
  | {placed()}? ID path? AT expr (block | ';')      # placedStmt  // `bearing A at 30 mm { … }`, `gear hs.pinion at 175 mm;`
  | ID ID block                                    # memberStmt  // `shaft input { … }`
  | path block                                     # blockStmt  // `rating { … }`, `ring.cutter { … }`
  | ID ';'                                         # flagStmt
  ;

domain
  : tolExpr '..' tolExpr                           # rangeDomain
  | '{' expr (',' expr)* '}'                       # setDomain
  | path                                           # namedDomain
  ;

path : ID ('.' ID)* ;

expr
  : FORALL ID IN orExpr ':' expr                   # forallExpr
  | orExpr                                         # plainExpr
  ;

orExpr  : andExpr (OR andExpr)* ;
andExpr : notExpr (AND notExpr)* ;
notExpr : NOT notExpr | cmpExpr ;
cmpExpr : tolExpr (cmpOp tolExpr | IN tolExpr '..' tolExpr | IN setLit)? ;
cmpOp   : '==' | '!=' | '<' | '<=' | '>' | '>=' ;
tolExpr : addExpr (PLUSMINUS addExpr)? ;
addExpr : mulExpr (('+' | '-') mulExpr)* ;
mulExpr : unaryExpr (('*' | '/') unaryExpr)* ;
unaryExpr : '-' unaryExpr | powExpr ;
powExpr : postfixExpr ('^' unaryExpr)? ;
postfixExpr : primary (postfixOp)* ;
postfixOp : '.' ID | '(' (expr (',' expr)*)? ')' ;
primary
  : quantity
  | ID
  | STRING
  | TRUE
  | FALSE
  | '(' expr ')'
  | setLit
  ;
setLit : '{' expr (',' expr)* '}' ;

quantity : NUMBER ({sameLine()}? unit)? ;
unit : unitFactor ({glued()}? ('*' | '/') unitFactor)* ;
unitFactor : unitAtom ({glued()}? '^' '-'? NUMBER)? ;
unitAtom : ID | '%' | DEGSIGN | '(' unit ')' ;

IMPORT : 'import' ;  CONST : 'const' ;  PRESET : 'preset' ;  FOR : 'for' ;
GEARBOX : 'gearbox' ;  EXTENDS : 'extends' ;  STAGE : 'stage' ;  WITH : 'with' ;
LIKE : 'like' ;  IN : 'in' ;  LET : 'let' ;  REQUIRE : 'require' ;  FORALL : 'forall' ;
INTERCHANGEABLE : 'interchangeable' ;  MINIMIZE : 'minimize' ;  MAXIMIZE : 'maximize' ;
OPERATING : 'operating' ;  SCENE : 'scene' ;  ON : 'on' ;  EFFECTS : 'effects' ;
MODIFY : 'modify' ;  SPLIT : 'split' ;  STUDY : 'study' ;  SWEEP : 'sweep' ;
STEP : 'step' ;  OF : 'of' ;  OUTPUT : 'output' ;  REPORT : 'report' ;  TOP : 'top' ;
SORT : 'sort' ;  BY : 'by' ;  COLUMNS : 'columns' ;  WHEN : 'when' ;  AND : 'and' ;
OR : 'or' ;  NOT : 'not' ;  TRUE : 'true' ;  FALSE : 'false' ;  AT : 'at' ;

PLUSMINUS : '+-' | '\u00B1' ;
DEGSIGN : '\u00B0' ;
// A fraction needs a digit after the point, so `11..25` lexes as 11, .., 25.
NUMBER : [0-9]+ ('.' [0-9]+)? ([eE] [+-]? [0-9]+)? ;
ID : [A-Za-z_\u00B5\u03BC] [A-Za-z0-9_]* ;
STRING : '"' (~["\\\r\n] | '\\' .)* '"' ;
LINE_COMMENT : '//' ~[\r\n]* -> channel(HIDDEN) ;
BLOCK_COMMENT : '/*' .*? '*/' -> channel(HIDDEN) ;
WS : [ \t\r\n]+ -> channel(HIDDEN) ;
// Lexical errors become tokens off the parser's channel; the front end reports them
// itself, so the lexer never prints and the parser sees only well-formed tokens.
// Never contains `*/`, or it would outmatch a closed comment that text follows.
UNTERMINATED_COMMENT : '/*' (~[*] | '*'+ ~[*/])* '*'* EOF -> channel(2) ;
UNTERMINATED_STRING : '"' (~["\\\r\n] | '\\' .)* -> channel(2) ;
BAD_CHAR : . -> channel(2) ;
