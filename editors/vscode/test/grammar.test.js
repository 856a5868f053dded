// Checks syntaxes/gbx.tmLanguage.json with plain Node (no VS Code, no network):
//   node test/grammar.test.js
//
// 1. the grammar is valid JSON and every `include` names a rule that exists;
// 2. every regular expression (`match`, `begin`, `end`, `while`) compiles with JavaScript's
//    RegExp, also in Unicode mode, which rejects Oniguruma-only syntax such as `\h`, `\A`,
//    `\G`, `\z`, atomic groups and possessive quantifiers;
// 3. every keyword of the lexer in grammar/Gbx.g4 is highlighted as a keyword, not as a
//    plain name;
// 4. sample lines and the project's own specs (specs/, stdlib/) get the expected scopes,
//    using a small one-line tokenizer that picks rules the way TextMate does (leftmost
//    match first, the earlier rule on a tie).
// Exits with status 1 on the first failing check group, after printing every failure.
'use strict';

const fs = require('fs');
const path = require('path');

const root = path.resolve(__dirname, '..');
const repo = path.resolve(root, '..', '..');
const grammarPath = path.join(root, 'syntaxes', 'gbx.tmLanguage.json');
const g4Path = path.join(repo, 'grammar', 'Gbx.g4');

const failures = [];
const fail = (msg) => failures.push(msg);
let checks = 0;
const check = (ok, msg) => {
  checks++;
  if (!ok) fail(msg);
};

// ---- 1. JSON and includes -------------------------------------------------------------
let grammar;
try {
  grammar = JSON.parse(fs.readFileSync(grammarPath, 'utf8'));
} catch (err) {
  console.error(`FAIL ${grammarPath}: ${err.message}`);
  process.exit(1);
}
check(grammar.scopeName === 'source.gbx', `scopeName is ${grammar.scopeName}, expected source.gbx`);
check(Array.isArray(grammar.patterns) && grammar.patterns.length > 0, 'top-level patterns missing');

const repository = grammar.repository || {};
const rules = []; // [where, rule]
(function walk(node, where) {
  if (Array.isArray(node)) {
    node.forEach((n, i) => walk(n, `${where}[${i}]`));
    return;
  }
  if (!node || typeof node !== 'object') return;
  if ('match' in node || 'begin' in node || 'include' in node) rules.push([where, node]);
  for (const [key, value] of Object.entries(node)) {
    if (key === 'patterns' || key === 'repository' || /^[0-9]+$/.test(key)) walk(value, `${where}.${key}`);
    else if (key === 'captures' || key === 'beginCaptures' || key === 'endCaptures') walk(value, `${where}.${key}`);
    else if (where.endsWith('.repository')) walk(value, `${where}.${key}`);
  }
})(grammar, '$');

for (const [where, rule] of rules) {
  if (!('include' in rule)) continue;
  const inc = rule.include;
  if (inc === '$self' || inc === '$base') continue;
  check(inc.startsWith('#') && inc.slice(1) in repository, `${where}: include ${inc} names no rule`);
}

// ---- 2. every regex compiles ----------------------------------------------------------
let regexCount = 0;
for (const [where, rule] of rules) {
  for (const key of ['match', 'begin', 'end', 'while']) {
    if (!(key in rule)) continue;
    regexCount++;
    for (const flags of ['', 'u']) {
      try {
        new RegExp(rule[key], flags);
        checks++;
      } catch (err) {
        fail(`${where}.${key} does not compile with RegExp(…, '${flags}'): ${err.message}`);
      }
    }
  }
}
check(regexCount > 20, `only ${regexCount} regular expressions found`);

// ---- a one-line tokenizer -------------------------------------------------------------
function flatten(patterns, out = []) {
  for (const p of patterns) {
    if (p.include) {
      const target = p.include === '$self' || p.include === '$base' ? grammar : repository[p.include.slice(1)];
      if (target) flatten(target.patterns || [target], out);
    } else if (p.match || p.begin) {
      out.push(p);
    } else if (p.patterns) {
      flatten(p.patterns, out);
    }
  }
  return out;
}
const compile = (patterns) =>
  flatten(patterns).map((p) => ({
    rule: p,
    re: new RegExp(p.match || p.begin, 'gd'),
    end: p.end ? new RegExp(p.end, 'gd') : null,
    inner: p.end ? compile(p.patterns || []) : [],
  }));
const compiled = compile(grammar.patterns);

// Returns, for each character of `line`, the list of scope names covering it.
function tokenize(line) {
  const scopes = Array.from(line, () => []);
  const mark = (from, to, name) => {
    if (!name) return;
    for (let i = from; i < to; i++) scopes[i].push(name);
  };
  const markCaptures = (m, caps) => {
    if (!caps) return;
    for (const [k, v] of Object.entries(caps)) {
      const span = m.indices[Number(k)];
      if (span) mark(span[0], span[1], v.name);
    }
  };
  // Scans `line` from `pos` with `candidates`; inside a begin/end rule, `end` wins a tie
  // with the rule's own patterns, as in TextMate. Returns where the scan stopped.
  const scan = (pos, candidates, end) => {
    while (pos <= line.length) {
      let best = null;
      for (const c of candidates) {
        c.re.lastIndex = pos;
        const m = c.re.exec(line);
        if (m && (!best || m.index < best.m.index)) best = { c, m };
      }
      if (end) {
        end.lastIndex = pos;
        const e = end.exec(line);
        if (e && (!best || e.index <= best.m.index)) return { stop: e.index + e[0].length, e };
      }
      if (!best || pos === line.length) return { stop: line.length, e: null };
      const { c, m } = best;
      let stop = m.index + m[0].length;
      if (c.end) {
        const inner = scan(stop, c.inner, c.end);
        mark(m.index, inner.stop, c.rule.name);
        markCaptures(m, c.rule.beginCaptures || c.rule.captures);
        if (inner.e) markCaptures(inner.e, c.rule.endCaptures || c.rule.captures);
        stop = inner.stop;
      } else {
        mark(m.index, stop, c.rule.name);
        markCaptures(m, c.rule.captures);
      }
      pos = stop > m.index ? stop : m.index + 1;
    }
    return { stop: line.length, e: null };
  };
  scan(0, compiled, null);
  return scopes;
}

// The scopes at the `nth` occurrence of `text` in `line`, joined by spaces.
function scopeAt(line, text, nth = 0) {
  let at = -1;
  for (let i = 0; i <= nth; i++) {
    at = line.indexOf(text, at + 1);
    if (at < 0) return `<"${text}" not in line>`;
  }
  const s = tokenize(line);
  // The scopes every character of `text` shares.
  let common = s[at];
  for (let i = at + 1; i < at + text.length; i++) common = common.filter((x) => s[i].includes(x));
  return common.join(' ');
}

// ---- 3. the lexer's keywords ----------------------------------------------------------
let g4;
try {
  g4 = fs.readFileSync(g4Path, 'utf8');
} catch (err) {
  console.error(`FAIL cannot read ${g4Path}: ${err.message}`);
  process.exit(1);
}
const keywords = [];
for (const m of g4.matchAll(/\b([A-Z][A-Z_]*)\s*:\s*'([A-Za-z_]+)'\s*;/g)) keywords.push(m[2]);
check(keywords.length >= 30, `only ${keywords.length} keywords read from Gbx.g4`);
const grammarText = JSON.stringify(grammar);
for (const kw of keywords) {
  check(new RegExp(`\\b${kw}\\b`).test(grammarText), `keyword "${kw}" does not appear in the grammar`);
  const scope = scopeAt(kw, kw);
  check(
    /\b(keyword|storage|constant\.language)\./.test(scope),
    `keyword "${kw}" standing alone is scoped "${scope}", expected a keyword scope`,
  );
}

// ---- 4. sample lines ------------------------------------------------------------------
const expect = (line, text, scope, nth = 0) => {
  const got = scopeAt(line, text, nth);
  check(got.split(' ').includes(scope), `in ${JSON.stringify(line)}: "${text}" is "${got}", expected ${scope}`);
};
const expectNot = (line, text, prefix, nth = 0) => {
  const got = scopeAt(line, text, nth);
  check(!got.split(' ').some((s) => s.startsWith(prefix)), `in ${JSON.stringify(line)}: "${text}" is "${got}", expected no ${prefix}`);
};

// comments and strings
expect('// gearbox Foo { }', 'gearbox', 'comment.line.double-slash.gbx');
expect('/* stage a: spur */ gearbox X {', 'spur', 'comment.block.gbx');
expect('/* stage a: spur */ gearbox X {', 'gearbox', 'storage.type.gearbox.gbx');
expect('import "local/presets.gbx";', '"local/presets.gbx"', 'string.quoted.double.gbx');
expect('import "a\\"b.gbx";', 'b.gbx', 'string.quoted.double.gbx');
expect('import klingelnberg;', 'klingelnberg', 'entity.name.namespace.gbx');

// declarations
expect('gearbox MarineReducer {', 'MarineReducer', 'entity.name.type.gearbox.gbx');
expect('gearbox B extends MarineReducer {', 'B', 'entity.name.type.gearbox.gbx');
expect('gearbox B extends MarineReducer {', 'extends', 'storage.modifier.extends.gbx');
expect('gearbox B extends MarineReducer {', 'MarineReducer', 'entity.other.inherited-class.gbx');
expect('  stage main: helical {', 'main', 'entity.name.type.stage.gbx');
expect('  stage main: helical {', 'helical', 'support.type.stage-kind.gbx');
expect('  stage transfer: idler {', 'idler', 'support.type.stage-kind.gbx');
expect('  stage b: bevel with klingelnberg, gleason {', 'with', 'storage.modifier.gbx');
expect('  stage lower like upper;', 'lower', 'entity.name.type.stage.gbx');
expect('  stage lower like upper;', 'like', 'storage.modifier.like.gbx');
expect('preset klingelnberg for bevel {', 'klingelnberg', 'entity.name.type.preset.gbx');
expect('preset klingelnberg for bevel {', 'bevel', 'support.type.stage-kind.gbx');
expect('material steel_20CrMnMo {', 'steel_20CrMnMo', 'entity.name.type.material.gbx');
expect('  scene vibration on main {', 'vibration', 'entity.name.function.scene.gbx');
expect('  scene vibration on main {', 'on', 'keyword.control.gbx', 1);
expect('  study cost_of_accuracy {', 'cost_of_accuracy', 'entity.name.function.study.gbx');
expect('  split sharing {', 'sharing', 'entity.name.function.split.gbx');
expect('const target = 5.8;', 'target', 'entity.name.variable.constant.gbx');
expect('  let gap = wheel.z - pinion.z;', 'gap', 'entity.name.variable.let.gbx');
expect('require forall z in teeth: coprime(z, 5);', 'z', 'variable.parameter.gbx');
expect('require forall z in teeth: coprime(z, 5);', 'coprime', 'support.function.builtin.gbx');
// `idler` is also the middle gear of an idler stage
expectNot('    idler.z  = 30;', 'idler', 'support.type');
expect('    idler.z  = 30;', 'z', 'variable.other.property.gbx');

// effects, blocks, functions, settings
expect('      varying_stiffness { harmonics = 5; }', 'varying_stiffness', 'support.class.effect.gbx');
expect('      loaded_mesh { slices = 40; positions = 64; }', 'loaded_mesh', 'support.class.effect.gbx');
expectNot('      hertz_contact { damping = 0.01 * stiffness; }', 'damping', 'support.class');
expect('    output rms(transmission_error), plot(acceleration);', 'rms', 'support.function.signal.gbx');
expectNot('    output rms(transmission_error), plot(acceleration);', 'transmission_error', 'support.class');
expect('  tolerances { main.face_width +- 1 mm; }', 'tolerances', 'keyword.other.block.gbx');
expect('    rating {', 'rating', 'keyword.other.block.gbx');
expect('      load_spectrum {', 'load_spectrum', 'keyword.other.block.gbx');
expect('      face_load_factor = contact_analysis;', 'contact_analysis', 'constant.language.symbol.gbx');
expect('    accuracy { method = rk8pd; rtol = 1e-9; }', 'accuracy', 'keyword.other.block.gbx');
expect('    accuracy { method = rk8pd; rtol = 1e-9; }', 'rk8pd', 'constant.language.symbol.gbx');
expect('    install = preloaded;', 'preloaded', 'constant.language.symbol.gbx');
expect('    work_precision of vibration;', 'work_precision', 'keyword.other.study.gbx');
expect('  minimize 0.6 * relative(worst(vibration.rms(acceleration)));', 'worst', 'support.function.builtin.gbx');
expect('  minimize 0.6 * relative(worst(vibration.rms(acceleration)));', 'rms', 'support.function.signal.gbx');
expect('  report { columns quantile(vibration.rms(acceleration), 0.95); }', 'quantile', 'support.function.builtin.gbx');

// numbers and units
const quantities = [
  ['normal_module = 3 mm;', '3', 'mm'],
  ['rtol = 1e-9;', '1e-9', null],
  ['input_speed = 12000 rpm;', '12000', 'rpm'],
  ['input_torque = 91670 N*m;', '91670', 'N*m'],
  ['pressure_angle = 20 deg;', '20', 'deg'],
  ['tip_relief_height = 30% * whole_depth;', '30', '%'],
  ['density = 7850 kg/m^3;', '7850', 'kg/m^3'],
  ['mesh_stiffness = 16.35 N/(mm*um);', '16.35', 'N/(mm*um)'],
  ['shaft_angle = 90°;', '90', '°'],
  ['amplitude = 11 µm;', '11', 'µm'],
  ['viscosity_40 = 150 mm^2/s;', '150', 'mm^2/s'],
  ['speed = 1800 deg/s;', '1800', 'deg/s'],
  ['record = 1 mesh_period;', '1', 'mesh_period'],
  ['settle = 200 mesh_periods;', '200', 'mesh_periods'],
  ['youngs_modulus = 2.06e11 Pa;', '2.06e11', 'Pa'],
  ['power = 3 MW;', '3', 'MW'],
];
for (const [line, num, unit] of quantities) {
  expect(line, num, 'constant.numeric.gbx');
  if (unit) expect(line, unit, 'keyword.other.unit.gbx');
}
expect('pinion.z in 11..25;', '11', 'constant.numeric.gbx');
expect('pinion.z in 11..25;', '..', 'keyword.operator.range.gbx');
expect('pinion.z in 11..25;', '25', 'constant.numeric.gbx');
expect('spiral_angle in 30..35 deg;', 'deg', 'keyword.other.unit.gbx');
expect('lubricant { oil_temperature = 80 degC; }', 'degC', 'keyword.other.unit.gbx');
expect('require hs.contact_temperature - 20 degC < 150 K;', 'K', 'keyword.other.unit.gbx');
expect('require ratio == 3.952 +- 1%;', '+-', 'keyword.operator.tolerance.gbx');
expect('require ratio == 3.952 +- 1%;', '%', 'keyword.other.unit.gbx');
expect('require ratio == 3.952 ± 0.01;', '±', 'keyword.operator.tolerance.gbx');
expect('require ratio == 3.952 +- 1%;', '==', 'keyword.operator.comparison.gbx');
expect('tip_relief_height = 22% * whole_depth;', '*', 'keyword.operator.arithmetic.gbx');
expectNot('tip_relief_height = 22% * whole_depth;', 'whole_depth', 'keyword.other.unit');
expectNot('face_width = 1.15 * pinion.d;', 'pinion', 'keyword.other.unit');
expectNot('x = 5 main;', 'main', 'keyword.other.unit');
expectNot('method = rk8pd;', '8', 'constant.numeric');
expectNot('require a == 5 and b;', 'and', 'keyword.other.unit');
expect('require a == 5 and b;', 'and', 'keyword.operator.logical.gbx');
expect('pinion.thermal_lead_relief = 8 um when pitch_line_velocity > 100 m/s;', 'when', 'keyword.control.gbx');
expect('pinion.thermal_lead_relief = 8 um when pitch_line_velocity > 100 m/s;', 'm/s', 'keyword.other.unit.gbx');
expect('sweep sharing.torsion_shaft.diameter in 60..120 mm step 10 mm;', 'step', 'keyword.control.gbx');
expect('sweep sharing.torsion_shaft.diameter in 60..120 mm step 10 mm;', 'mm', 'keyword.other.unit.gbx', 1);

// ---- 5. the project's specs -----------------------------------------------------------
// Outside comments and strings, a reserved word is never a plain name, and a number is a
// number.
const reserved = new Set(keywords);
const corpus = [];
for (const dir of ['specs', 'stdlib']) {
  const full = path.join(repo, dir);
  if (!fs.existsSync(full)) continue;
  for (const f of fs.readdirSync(full)) if (f.endsWith('.gbx')) corpus.push(path.join(full, f));
}
check(corpus.length > 0, 'no .gbx files found under specs/ or stdlib/');
for (const file of corpus) {
  const rel = path.relative(repo, file);
  fs.readFileSync(file, 'utf8')
    .split(/\r?\n/)
    .forEach((line, i) => {
      const s = tokenize(line);
      for (const m of line.matchAll(/[A-Za-z_][A-Za-z0-9_]*|[0-9]+(?:\.[0-9]+)?(?:[eE][+-]?[0-9]+)?/g)) {
        const scopes = s[m.index];
        if (scopes.some((x) => x.startsWith('comment.') || x.startsWith('string.'))) continue;
        const word = m[0];
        if (reserved.has(word)) {
          check(!scopes.some((x) => x.startsWith('variable.')), `${rel}:${i + 1}: keyword "${word}" scoped ${scopes.join(' ')}`);
        } else if (/^[0-9]/.test(word) && (m.index === 0 || !/[A-Za-z0-9_^]/.test(line[m.index - 1]))) {
          check(scopes.includes('constant.numeric.gbx'), `${rel}:${i + 1}: number "${word}" scoped ${scopes.join(' ')}`);
        }
      }
    });
}

// ---- result ---------------------------------------------------------------------------
if (failures.length) {
  for (const f of failures) console.error(`FAIL ${f}`);
  console.error(`${failures.length} of ${checks} checks failed`);
  process.exit(1);
}
console.log(
  `ok: ${checks} checks; ${regexCount} regular expressions compile; ${keywords.length} keywords of Gbx.g4 highlighted; ${corpus.length} spec files tokenized`,
);
