#include "driver/Golden.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "driver/Driver.h"

namespace gbx::driver {

namespace fs = std::filesystem;

namespace {

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  std::string x;
  while (in >> x) w.push_back(x);
  return w;
}

// `// KEY: value` among the spec's leading comment lines.
std::optional<std::string> header(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::string line, tag = "// " + key + ":";
  while (std::getline(in, line) && line.rfind("//", 0) == 0)
    if (line.rfind(tag, 0) == 0) return line.substr(tag.size());
  return std::nullopt;
}

void addCase(const fs::path& gbx, std::vector<GoldenCase>& out) {
  GoldenCase c;
  c.gbx = gbx.string();
  fs::path exp = gbx;
  exp.replace_extension(".expected");
  c.expected = exp.string();
  c.name = gbx.parent_path().filename().string() + "/" + gbx.stem().string();
  std::string text = readAll(gbx);
  fs::path folderArgs = gbx.parent_path() / "golden.args";
  if (auto a = header(text, "ARGS")) c.args = words(*a);
  else if (fs::exists(folderArgs)) c.args = words(readAll(folderArgs));
  else c.args = {"solve"};
  if (auto t = header(text, "TOLERANCE")) c.tolerance = std::strtod(t->c_str(), nullptr);
  out.push_back(std::move(c));
}

// A line split into its numbers and the text around them.
struct Split {
  std::vector<std::string> text;
  std::vector<double> numbers;
  std::vector<bool> whole;  // written without a point or an exponent: a count, teeth, a rank
};

Split splitNumbers(const std::string& line) {
  Split s;
  std::string cur;
  size_t i = 0;
  while (i < line.size()) {
    char c = line[i];
    bool starts = std::isdigit(static_cast<unsigned char>(c)) ||
                  ((c == '-' || c == '.') && i + 1 < line.size() && std::isdigit(static_cast<unsigned char>(line[i + 1])));
    // A digit inside a word (`E0201`, `rk8pd`, `s1`) is part of the word.
    bool inWord = i > 0 && (std::isalnum(static_cast<unsigned char>(line[i - 1])) || line[i - 1] == '_');
    if (!starts || inWord) {
      cur += c;
      ++i;
      continue;
    }
    char* end = nullptr;
    double v = std::strtod(line.c_str() + i, &end);
    size_t n = static_cast<size_t>(end - (line.c_str() + i));
    if (n == 0) {
      cur += c;
      ++i;
      continue;
    }
    s.text.push_back(cur);
    cur.clear();
    s.numbers.push_back(v);
    s.whole.push_back(line.find_first_of(".eE", i) >= i + n);
    i += n;
  }
  s.text.push_back(cur);
  return s;
}

} // namespace

std::vector<std::string> gbxFilesBelow(const std::string& folder, std::string& problem) {
  std::error_code ec;
  std::vector<std::string> out;
  fs::path at = folder;  // the folder being entered when a step fails
  for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end;) {
    at = it->path();
    if (at.extension() == ".gbx" && it->is_regular_file(ec)) out.push_back(at.string());
    it.increment(ec);
  }
  std::error_code ignored;
  if (ec) problem = fmt::format("cannot read the folder `{}`: {}", fs::is_directory(at, ignored) ? at.string() : folder, ec.message());
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<GoldenCase> discoverGolden(const std::vector<std::string>& paths, std::vector<std::string>& problems) {
  std::vector<GoldenCase> out;
  for (const auto& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::string unreadable;  // a folder that cannot be read holds no cases, as before
      for (const auto& f : gbxFilesBelow(p, unreadable)) addCase(f, out);
    } else if (fs::is_regular_file(p, ec) && fs::path(p).extension() == ".gbx") {
      addCase(p, out);
    } else {
      problems.push_back(fmt::format("`{}` is neither a .gbx file nor a folder", p));
    }
  }
  return out;
}

std::string captureGolden(const GoldenCase& c, const GoldenOptions& o) {
  fs::path file(c.gbx);
  fs::path dir = file.parent_path();
  std::vector<std::string> args = c.args;
  // CPU times differ from run to run and machine to machine: never part of a golden file.
  bool solve = !args.empty() && args[0] == "solve";
  if (solve && !o.timings && std::find(args.begin(), args.end(), "--no-timings") == args.end()) args.push_back("--no-timings");
  args.push_back(file.filename().string());
  std::ostringstream out, err;
  fs::path cwd = fs::current_path();
  if (!dir.empty()) fs::current_path(dir);
  int status = run(args, out, err);
  fs::current_path(cwd);
  std::string text = out.str() + err.str();
  if (!text.empty() && text.back() != '\n') text += "\n";
  return text + fmt::format("[exit {}]\n", status);
}

bool equalWithin(const std::string& expected, const std::string& actual, double tolerance) {
  if (expected == actual) return true;
  if (tolerance <= 0) return false;
  std::istringstream a(expected), b(actual);
  std::string x, y;
  while (true) {
    bool ga = static_cast<bool>(std::getline(a, x)), gb = static_cast<bool>(std::getline(b, y));
    if (!ga || !gb) return ga == gb;
    if (x == y) continue;
    Split sx = splitNumbers(x), sy = splitNumbers(y);
    if (sx.text != sy.text || sx.numbers.size() != sy.numbers.size()) return false;
    for (size_t i = 0; i < sx.numbers.size(); ++i) {
      double u = sx.numbers[i], v = sy.numbers[i];
      // The tolerance is for the last digits of real numbers: a design count, tooth counts
      // and any other whole number compare exactly (a number written whole on one side and
      // with a point on the other is a real number that printed short).
      if (sx.whole[i] && sy.whole[i]) {
        if (u != v) return false;
        continue;
      }
      if (std::fabs(u - v) > tolerance * std::max(std::fabs(u), std::fabs(v))) return false;
    }
  }
}

GoldenOutcome runGolden(const GoldenCase& c, const GoldenOptions& o) {
  std::string actual = captureGolden(c, o);
  GoldenOutcome r;
  std::error_code ec;
  bool exists = fs::exists(c.expected, ec);
  if (o.update) {
    if (!exists || readAll(c.expected) != actual) {
      std::ofstream(c.expected, std::ios::binary) << actual;
      r.status = GoldenOutcome::Updated;
    }
    return r;
  }
  if (!exists) {
    r.status = GoldenOutcome::Missing;
    return r;
  }
  std::string expected = readAll(c.expected);
  if (!equalWithin(expected, actual, c.tolerance)) {
    r.status = GoldenOutcome::Fail;
    r.diff = unifiedDiff(expected, actual, c.expected, "actual");
  }
  return r;
}

namespace {
// The lines of a text; a last line without a line break carries patch(1)'s marker, so that
// it differs from the same line with one and the diff says so.
std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> v;
  std::istringstream in(s);
  std::string l;
  while (std::getline(in, l)) v.push_back(l);
  if (!s.empty() && s.back() != '\n') v.back() += "\n\\ No newline at end of file";
  return v;
}
} // namespace

std::string unifiedDiff(const std::string& expected, const std::string& actual, const std::string& expectedName,
                        const std::string& actualName) {
  auto a = lines(expected), b = lines(actual);
  struct Op {
    char kind;
    size_t ai, bi;  // the line's index in `a` (for ' ' and '-') and in `b` (for ' ' and '+')
  };
  std::vector<Op> ops;
  // The lines both share at the start and the end need no table.
  size_t pre = 0, suf = 0;
  while (pre < a.size() && pre < b.size() && a[pre] == b[pre]) ++pre;
  while (suf < a.size() - pre && suf < b.size() - pre && a[a.size() - 1 - suf] == b[b.size() - 1 - suf]) ++suf;
  for (size_t k = 0; k < pre; ++k) ops.push_back({' ', k, k});
  size_t n = a.size() - pre - suf, m = b.size() - pre - suf;
  if (n * m <= 4'000'000) {
    // LCS table of what lies between; bounded, so a long file costs at most 16 MB here.
    std::vector<std::vector<unsigned>> L(n + 1, std::vector<unsigned>(m + 1, 0));
    for (size_t i = n; i-- > 0;)
      for (size_t j = m; j-- > 0;)
        L[i][j] = a[pre + i] == b[pre + j] ? L[i + 1][j + 1] + 1 : std::max(L[i + 1][j], L[i][j + 1]);
    size_t i = 0, j = 0;
    while (i < n || j < m) {
      if (i < n && j < m && a[pre + i] == b[pre + j]) {
        ops.push_back({' ', pre + i++, pre + j++});
      } else if (i < n && (j == m || L[i + 1][j] >= L[i][j + 1])) {
        ops.push_back({'-', pre + i++, pre + j});
      } else {
        ops.push_back({'+', pre + i, pre + j++});
      }
    }
  } else {
    for (size_t i = 0; i < n; ++i) ops.push_back({'-', pre + i, pre});
    for (size_t j = 0; j < m; ++j) ops.push_back({'+', pre + n, pre + j});
  }
  for (size_t k = 0; k < suf; ++k) ops.push_back({' ', pre + n + k, pre + m + k});

  std::string out = fmt::format("--- {}\n+++ {}\n", expectedName, actualName);
  const size_t ctx = 3;
  size_t k = 0;
  while (k < ops.size()) {
    if (ops[k].kind == ' ') {
      ++k;
      continue;
    }
    size_t start = k >= ctx ? k - ctx : 0, end = k;
    while (end < ops.size()) {
      if (ops[end].kind != ' ') {
        ++end;
        continue;
      }
      size_t run = end;
      while (run < ops.size() && ops[run].kind == ' ') ++run;
      if (run - end > 2 * ctx || run == ops.size()) {
        end = std::min(ops.size(), end + ctx);
        break;
      }
      end = run;
    }
    size_t na = 0, nb = 0;
    for (size_t x = start; x < end; ++x) {
      na += ops[x].kind != '+';
      nb += ops[x].kind != '-';
    }
    // Line numbers as patch(1) reads them: an empty side names the line before it.
    out += fmt::format("@@ -{},{} +{},{} @@\n", na ? ops[start].ai + 1 : ops[start].ai, na, nb ? ops[start].bi + 1 : ops[start].bi, nb);
    for (size_t x = start; x < end; ++x)
      out += std::string(1, ops[x].kind) + (ops[x].kind == '+' ? b[ops[x].bi] : a[ops[x].ai]) + "\n";
    k = end;
  }
  return out;
}

} // namespace gbx::driver
