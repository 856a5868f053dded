// Sizing benchmark: the everyday job of sizing a two-stage helical reducer, its face widths
// continuous ranges under safety rules, the mass minimised.
//   sizing_bench GBXC reducer
//     `GBXC solve --jobs 1` on the whole spec, three times: the CPU seconds of each (the
//     child's user + system time), then checks on design 1 made as a user would, with gbxc
//     itself: pinned at its printed values it is one design; with 0.1 mm less face width on
//     either stage it is none; the same spec with each face width a list of eight values
//     gives a best design no lighter. One line of key=value pairs.
//   sizing_bench GBXC narrowed
//     a narrowed copy (pinions 17..20, wheels 80..95) solved by gbxc, against a brute force
//     in this process: every tooth-count and module combination in the ratio window, each
//     stage's face width scanned upward in 0.1 mm steps until its safeties hold (the mass
//     rises with the face width, so the first that holds is the stage's lightest on the
//     grid). Times of both, the best design of each, whether gbxc's best 10 are the brute
//     force's (each of gbxc's face widths at most one grid step below the brute force's).
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <numeric>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "driver/Driver.h"
#include "model/Evaluator.h"

using namespace gbx;

namespace {

struct Ranges {
  std::string pinions, wheels;
  std::string hsWidth = "in 30..90 mm", lsWidth = "in 50..140 mm";
  std::string hsPin, lsPin; // pinned tooth counts and modules, when checking one design
};

std::string stage(const std::string& name, const Ranges& r, const std::string& modules, const std::string& helix,
                  const std::string& width, const std::string& pin) {
  std::string teeth = pin.empty() ? fmt::format("pinion.z in {};  wheel.z in {};\n    normal_module in {{{}}};",
                                                r.pinions, r.wheels, modules)
                                  : pin;
  return fmt::format(R"(  stage {}: helical {{
    {}
    helix_angle = {};
    face_width {};
    material = steel_18CrNiMo7_6;
    accuracy = 6;
    rating {{
      application_factor = 1.25;
      life = 20000 h;
      lubricant {{ viscosity_40 = 150 mm^2/s; }}
      roughness {{ flank = 0.6 um; root = 3.0 um; }}
      min_safety {{ contact = 1.2; bending = 1.5; }}
    }}
  }}
)",
                     name, teeth, helix, width);
}

// The issue's reducer: 55 kW at 1480 rpm, ratio 22.4 +- 2 %, the safeties of both stages.
std::string reducer(const Ranges& r) {
  std::string t = "import materials;\ngearbox Reducer {\n";
  t += stage("hs", r, "2 mm, 2.5 mm, 3 mm, 4 mm", "12 deg", r.hsWidth, r.hsPin);
  t += stage("ls", r, "3 mm, 4 mm, 5 mm, 6 mm", "10 deg", r.lsWidth, r.lsPin);
  t += R"(  operating { input_speed = 1480 rpm; power = 55 kW; }
  require ratio == 22.4 +- 2%;
  require hs.pinion.contact_safety >= 1.2;  require hs.wheel.contact_safety >= 1.2;
  require hs.pinion.bending_safety >= 1.5;  require hs.wheel.bending_safety >= 1.5;
  require ls.pinion.contact_safety >= 1.2;  require ls.wheel.contact_safety >= 1.2;
  require ls.pinion.bending_safety >= 1.5;  require ls.wheel.bending_safety >= 1.5;
  minimize hs.mass + ls.mass;
}
)";
  return t;
}

struct Run {
  std::string out;
  double cpu = 0;
};

// `gbxc solve FILE --jobs 1`: its output and the CPU seconds it took.
Run solve(const std::string& gbxc, const std::string& text) {
  char path[] = "/tmp/sizing_benchXXXXXX.gbx";
  int fd = mkstemps(path, 4);
  if (fd < 0) throw std::runtime_error("cannot create a temporary spec");
  close(fd);
  std::ofstream(path) << text;
  rusage before{}, after{};
  getrusage(RUSAGE_CHILDREN, &before);
  FILE* p = popen(fmt::format("{} solve {} --jobs 1 --no-timings 2>&1", gbxc, path).c_str(), "r");
  Run r;
  char buf[4096];
  while (p && fgets(buf, sizeof buf, p))
    r.out += buf;
  if (p) pclose(p);
  getrusage(RUSAGE_CHILDREN, &after);
  auto secs = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  r.cpu = secs(after.ru_utime) - secs(before.ru_utime) + secs(after.ru_stime) - secs(before.ru_stime);
  std::remove(path);
  return r;
}

// Design 1 as the text report prints it.
struct Printed {
  std::map<std::string, std::string> values; // path -> printed value (with its unit)
  double mass = NAN;
  long long designs = -1;
};

Printed firstDesign(const std::string& out) {
  Printed p;
  std::smatch m;
  if (std::regex_search(out, m, std::regex(R"(: (\d+) designs?)"))) p.designs = std::stoll(m[1]);
  auto at = out.find("  design 1: ");
  if (at == std::string::npos) return p;
  // The line and its continuations (the text report wraps at 120 columns, indenting them).
  std::string line;
  for (size_t from = at + 12;;) {
    size_t end = out.find('\n', from);
    std::string part = out.substr(from, end == std::string::npos ? std::string::npos : end - from);
    line += (line.empty() ? "" : " ") + part.substr(part.find_first_not_of(' ') == std::string::npos ? 0 : part.find_first_not_of(' '));
    if (end == std::string::npos || out.compare(end + 1, 6, "      ") != 0) break;
    from = end + 1;
  }
  std::regex item(R"(([a-z_.]+) ([0-9.]+(?: mm)?)(?:,|$))");
  for (auto it = std::sregex_iterator(line.begin(), line.end(), item); it != std::sregex_iterator(); ++it)
    p.values[(*it)[1]] = (*it)[2];
  if (std::regex_search(line, m, std::regex(R"(\(hs\.mass \+ ls\.mass\) ([0-9.]+) kg)"))) p.mass = std::stod(m[1]);
  return p;
}

std::string pinned(const Printed& d, const std::string& s) {
  return fmt::format("pinion.z = {}; wheel.z = {}; normal_module = {};", d.values.at(s + ".pinion.z"),
                     d.values.at(s + ".wheel.z"), d.values.at(s + ".normal_module"));
}

double mm(const std::string& v) { return std::stod(v.substr(0, v.find(' '))); }

int reducerCase(const std::string& gbxc) {
  Ranges r;
  r.pinions = "17..30";
  r.wheels = "60..150";
  const std::string spec = reducer(r);
  std::vector<double> cpu;
  Run run;
  for (int i = 0; i < 3; ++i) {
    run = solve(gbxc, spec);
    cpu.push_back(run.cpu);
  }
  Printed d = firstDesign(run.out);
  if (d.designs <= 0 || std::isnan(d.mass)) {
    fmt::print(stderr, "no design 1 in:\n{}", run.out);
    return 1;
  }
  // Pinned at its printed values; then 0.1 mm narrower on each stage.
  Ranges pin = r;
  pin.hsPin = pinned(d, "hs");
  pin.lsPin = pinned(d, "ls");
  pin.hsWidth = "= " + d.values.at("hs.face_width");
  pin.lsWidth = "= " + d.values.at("ls.face_width");
  long long atPrinted = firstDesign(solve(gbxc, reducer(pin)).out).designs;
  Ranges thinHs = pin, thinLs = pin;
  thinHs.hsWidth = fmt::format("= {:.4f} mm", mm(d.values.at("hs.face_width")) - 0.1);
  thinLs.lsWidth = fmt::format("= {:.4f} mm", mm(d.values.at("ls.face_width")) - 0.1);
  long long hsThinner = firstDesign(solve(gbxc, reducer(thinHs)).out).designs;
  long long lsThinner = firstDesign(solve(gbxc, reducer(thinLs)).out).designs;
  // Face widths as lists of eight values.
  Ranges lists = r;
  lists.hsWidth = "in {30 mm, 38 mm, 47 mm, 55 mm, 64 mm, 72 mm, 81 mm, 90 mm}";
  lists.lsWidth = "in {50 mm, 63 mm, 76 mm, 89 mm, 101 mm, 114 mm, 127 mm, 140 mm}";
  Run listed = solve(gbxc, reducer(lists));
  Printed l = firstDesign(listed.out);
  std::sort(cpu.begin(), cpu.end());
  fmt::print("reducer designs={} cpu={:.3f},{:.3f},{:.3f} design1={}/{}+{}/{} m_n={}/{} b={}/{} mass={:.4f} "
             "pinned={} hs_minus_0.1mm={} ls_minus_0.1mm={} lists_designs={} lists_mass={:.4f} lists_cpu={:.3f}\n",
             d.designs, cpu[0], cpu[1], cpu[2], d.values["hs.pinion.z"], d.values["hs.wheel.z"],
             d.values["ls.pinion.z"], d.values["ls.wheel.z"], d.values["hs.normal_module"],
             d.values["ls.normal_module"], d.values["hs.face_width"], d.values["ls.face_width"], d.mass, atPrinted,
             hsThinner, lsThinner, l.designs, l.mass, listed.cpu);
  return atPrinted == 1 && hsThinner == 0 && lsThinner == 0 && d.mass <= l.mass ? 0 : 1;
}

// ---- the brute force over a face-width grid ------------------------------------------

struct Brute {
  double mass;
  std::vector<int> choice;
  double bHs, bLs;
};

std::vector<Brute> bruteForce(const std::string& text, double step) {
  auto c = driver::compileText("narrowed.gbx", text);
  if (!c->ok()) throw std::runtime_error(c->diags.renderText(c->sources));
  rt::Model m(c->program, c->program.gearboxes[0]);
  rt::Evaluator ev(m);
  auto slot = [&](const std::string& path) {
    for (size_t i = 0; i < m.slots.size(); ++i)
      if (m.slots[i].path == path) return i;
    throw std::runtime_error("no slot " + path);
  };
  auto freedom = [&](const std::string& path) {
    for (size_t i = 0; i < m.freedoms.size(); ++i)
      if (m.freedoms[i].path == path) return i;
    throw std::runtime_error("no freedom " + path);
  };
  const size_t fHs = freedom("hs.face_width"), fLs = freedom("ls.face_width");
  auto holds = [&](const rt::Assignment& a, const std::string& s) {
    for (const char* g : {"pinion", "wheel"}) {
      if (ev.quantity(fmt::format("{}.{}.contact_safety", s, g), a).mid() < 1.2) return false;
      if (ev.quantity(fmt::format("{}.{}.bending_safety", s, g), a).mid() < 1.5) return false;
    }
    return true;
  };
  // The first grid width from below where the stage's safeties hold, or NAN.
  auto scan = [&](rt::Assignment& a, size_t f, const std::string& s) {
    const double lo = m.freedoms[f].lo, hi = m.freedoms[f].hi;
    for (int i = 0;; ++i) {
      double b = std::min(hi, lo + step * i);
      a.box[f] = {b, b};
      if (holds(a, s)) return b;
      if (b >= hi) return std::nan("");
    }
  };
  std::vector<std::string> names = {"pinion.z", "wheel.z", "normal_module"};
  std::vector<size_t> hs, ls;
  for (const auto& n : names) {
    hs.push_back(slot("hs." + n));
    ls.push_back(slot("ls." + n));
  }
  auto combos = [&](const std::vector<size_t>& slots) {
    std::vector<std::vector<int>> out;
    for (size_t i = 0; i < m.slots[slots[0]].values.size(); ++i)
      for (size_t j = 0; j < m.slots[slots[1]].values.size(); ++j)
        for (size_t k = 0; k < m.slots[slots[2]].values.size(); ++k)
          out.push_back({static_cast<int>(i), static_cast<int>(j), static_cast<int>(k)});
    return out;
  };
  auto teeth = [&](size_t s, int i) { return static_cast<long long>(m.slots[s].values[static_cast<size_t>(i)].lo); };
  std::vector<Brute> out;
  std::map<std::vector<int>, double> hsWidth;
  for (const auto& h : combos(hs))
    for (const auto& l : combos(ls)) {
      // ratio == 22.4 +- 2 %: 21.952 <= product <= 22.848, in integers.
      long long num = teeth(hs[1], h[1]) * teeth(ls[1], l[1]), den = teeth(hs[0], h[0]) * teeth(ls[0], l[0]);
      if (num * 1000 < den * 21952 || num * 1000 > den * 22848) continue;
      rt::Assignment a(m);
      for (size_t i = 0; i < 3; ++i) {
        a.choice[hs[i]] = h[i];
        a.choice[ls[i]] = l[i];
      }
      if (!hsWidth.count(h)) hsWidth[h] = scan(a, fHs, "hs");
      double bHs = hsWidth[h];
      if (std::isnan(bHs)) continue;
      a.box[fHs] = {bHs, bHs};
      double bLs = scan(a, fLs, "ls");
      if (std::isnan(bLs)) continue;
      double mass = ev.quantity("hs.mass", a).mid() + ev.quantity("ls.mass", a).mid();
      out.push_back({mass, a.choice, bHs, bLs});
    }
  std::sort(out.begin(), out.end(), [](const Brute& x, const Brute& y) { return x.mass < y.mass; });
  return out;
}

int narrowedCase(const std::string& gbxc) {
  Ranges r;
  r.pinions = "17..20";
  r.wheels = "80..95";
  const std::string spec = reducer(r);
  const double step = 1e-4; // m: a 0.1 mm grid
  Run g = solve(gbxc, spec);
  std::clock_t c0 = std::clock();
  auto brute = bruteForce(spec, step);
  double bruteCpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  Printed d = firstDesign(g.out);
  // gbxc's rows: rank, the three values of each stage, the two face widths, ..., the mass.
  std::vector<std::vector<std::string>> rows;
  auto at = g.out.find("  rank ");
  std::istringstream lines(at == std::string::npos ? "" : g.out.substr(at));
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line) && rows.size() < 10) {
    std::istringstream ws(line);
    std::vector<std::string> w;
    for (std::string x; ws >> x;)
      w.push_back(x);
    if (w.empty() || !std::isdigit(static_cast<unsigned char>(w[0][0]))) break;
    rows.push_back(w);
  }
  if (std::getenv("SIZING_VERBOSE")) {
    for (size_t i = 0; i < 12 && i < brute.size(); ++i) {
      std::string ch;
      for (int x : brute[i].choice) ch += fmt::format("{} ", x);
      fmt::print(stderr, "brute {} {:.4f} {} b={:.1f}/{:.1f}\n", i + 1, brute[i].mass, ch, brute[i].bHs * 1e3, brute[i].bLs * 1e3);
    }
    fmt::print(stderr, "{}", g.out);
  }
  // Same best 10: the same masses to within one grid step of face width on each stage.
  size_t same = 0;
  for (size_t i = 0; i < rows.size() && i < brute.size(); ++i) {
    double mass = std::stod(rows[i].back());
    same += mass <= brute[i].mass + 1e-3 && mass >= brute[i].mass * (1 - 2e-3);
  }
  fmt::print("narrowed designs={} brute_designs={} gbxc_cpu={:.3f} brute_cpu={:.3f} ratio={:.1f} gbxc_mass={:.4f} "
             "brute_mass={:.4f} brute_b={:.1f}/{:.1f} same_top={}/{}\n",
             d.designs, brute.size(), g.cpu, bruteCpu, bruteCpu / g.cpu, d.mass, brute.empty() ? NAN : brute[0].mass,
             brute.empty() ? NAN : brute[0].bHs * 1e3, brute.empty() ? NAN : brute[0].bLs * 1e3, same, rows.size());
  return !brute.empty() && !rows.empty() && same == rows.size() ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    fmt::print(stderr, "usage: sizing_bench GBXC reducer|narrowed\n");
    return 2;
  }
  std::string gbxc = argv[1], which = argv[2];
  if (which == "reducer") return reducerCase(gbxc);
  if (which == "narrowed") return narrowedCase(gbxc);
  fmt::print(stderr, "unknown case {}\n", which);
  return 2;
}
