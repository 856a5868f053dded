// The loaded mesh for noise work (docs/dynamics.md), with asserted answers: the corner's
// separation outside the path against a rigid roll of the two gears worked in coordinates,
// the corner contact an unrelieved pair makes under load and long relief removes, one
// tooth's pitch deviation over the hunting period and its sidebands against a hand-made
// discrete Fourier transform, Harris's map of relief against load, and IEC 61672-1's
// A-weighting table.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "FlankPair.h"
#include "SceneFixture.h"
#include "driver/Driver.h"
#include "dynamics/CornerContact.h"
#include "dynamics/Levels.h"
#include "dynamics/LoadedMesh.h"
#include "dynamics/LoadedMeshInputs.h"
#include "dynamics/Scene.h"
#include "study/Sweep.h"

using namespace gbx::rt::dyn;
using gbx::rt::dyn::testing::pair;

namespace {

constexpr double kCPrime = 14e9; // 14 N/(mm*um)

struct Point {
  double x, y;
};
Point rotated(Point p, Point about, double angle) {
  double c = std::cos(angle), s = std::sin(angle), dx = p.x - about.x, dy = p.y - about.y;
  return {about.x + c * dx - s * dy, about.y + s * dx + c * dy};
}
double polar(Point p, Point about) { return std::atan2(p.y - about.y, p.x - about.x); }
double radius(Point p, Point about) { return std::hypot(p.x - about.x, p.y - about.y); }
double wrap(double a) { return std::remainder(a, 2 * M_PI); }

// The two gears in coordinates: the pinion about the origin turning clockwise, the wheel about
// (a, 0) counter-clockwise, the line of action from the pinion's base circle at angle alpha.
// A flank is an involute drawn by unwinding a thread from its base circle: the point at
// unwinding angle t from the thread's start angle c is rb (cos(c + t), sin(c + t)) + rb t
// (sin(c + t), -cos(c + t)).
struct Rig {
  double rb1, rb2, ra1, ra2, a, alpha, L, start, end;
  Point O1{0, 0}, O2;
  explicit Rig(const FlankGeometry& g)
      : rb1(g.rb1), rb2(g.rb2), ra1(g.ra1), ra2(g.ra2), a(g.centerDistance),
        alpha(g.workingPressureAngle), O2{g.centerDistance, 0} {
    L = a * std::sin(alpha);
    start = L - std::sqrt(ra2 * ra2 - rb2 * rb2);
    end = std::sqrt(ra1 * ra1 - rb1 * rb1);
  }
  // The point of the line of action u from the pinion's base circle.
  Point onLine(double u) const {
    return {rb1 * std::cos(alpha) + u * std::sin(alpha), rb1 * std::sin(alpha) - u * std::cos(alpha)};
  }
  // The polar angle about its centre of a flank's point at radius r, the flank passing
  // through the line of action at u (the thread leaving its base circle where the line
  // touches it).
  double pinionFlankAngle(double u, double r) const {
    double c = alpha - u / rb1, t = std::sqrt(r * r - rb1 * rb1) / rb1;
    Point p{rb1 * (std::cos(c + t) + t * std::sin(c + t)), rb1 * (std::sin(c + t) - t * std::cos(c + t))};
    return polar(p, O1);
  }
  double wheelFlankAngle(double u, double r) const {
    double c = M_PI + alpha - (L - u) / rb2, t = std::sqrt(r * r - rb2 * rb2) / rb2;
    Point p{O2.x + rb2 * (std::cos(c + t) + t * std::sin(c + t)), rb2 * (std::sin(c + t) - t * std::cos(c + t))};
    return polar(p, O2);
  }
  // Before the path: both gears rolled back by ds from where the wheel's tip corner meets the
  // line; the pinion's further turn, times rb1, until its flank passes through the corner.
  double wheelCorner(double ds) const {
    Point K = rotated(onLine(start), O2, -ds / rb2);
    double gamma = wrap(polar(K, O1) - pinionFlankAngle(start, radius(K, O1)));
    return rb1 * (ds / rb1 - gamma);
  }
  // Beyond the path: rolled on by ds from where the pinion's tip corner leaves the line; the
  // pinion's further turn until its corner reaches the wheel's flank (bisection).
  double pinionCorner(double ds) const {
    Point K0 = rotated(onLine(end), O1, -ds / rb1);
    auto side = [&](double delta) {
      Point K = rotated(K0, O1, -delta);
      return wrap(polar(K, O2) - (wheelFlankAngle(end, radius(K, O2)) + ds / rb2));
    };
    double lo = 0, hi = 0.05;
    for (int i = 0; i < 200; ++i) {
      double mid = 0.5 * (lo + hi);
      (side(mid) * side(lo) > 0 ? lo : hi) = mid;
    }
    return rb1 * 0.5 * (lo + hi);
  }
};

LoadedMeshInput spur(double load) { return pair(20, 40, 4e-3, 0, 0.040, kCPrime, load); }

} // namespace

// The corner's separation from the roll geometry in base-circle coordinates agrees with a
// rigid roll of the two gears drawn in coordinates, to a nanometre, and grows as s^2.
TEST(CornerContact, SeparationMatchesARigidRollOfTheGears) {
  LoadedMeshInput in = spur(1.0);
  Rig rig(in.g);
  double p = in.g.basePitch, path = rig.end - rig.start;
  for (double f : {0.01, 0.03, 0.1, 0.2}) {
    double ds = f * p;
    EXPECT_NEAR(cornerSeparation(in.g, -ds), rig.wheelCorner(ds), 1e-9)
        << "before the path by " << f << " base pitches";
    EXPECT_NEAR(cornerSeparation(in.g, path + ds), rig.pinionCorner(ds), 1e-9)
        << "beyond the path by " << f << " base pitches";
  }
  EXPECT_EQ(cornerSeparation(in.g, 0.5 * path), 0.0);
  // Quadratic: a tenth of the roll, a hundredth of the separation.
  double near = cornerSeparation(in.g, -0.01 * p), far = cornerSeparation(in.g, -0.1 * p);
  EXPECT_NEAR(far / near, 100.0, 10.0);
  EXPECT_GT(near, 0.0);
}

// An unrelieved spur pair under load: the next pair's tip corner closes before the path
// starts where the corner's separation falls below the loaded pair's approach. The positions
// where the transmission error drops are those a hand calculation predicts from the
// approach without corner contact; the first of them lies the extra roll before the start.
TEST(CornerContact, UnrelievedPairTouchesBeforeThePathByTheRollItsDeflectionCloses) {
  LoadedMeshInput in = spur(8000.0);
  in.slices = 1;
  in.positions = 4000;
  Rig rig(in.g);
  double p = in.g.basePitch, path = rig.end - rig.start, eps = path / p;
  LoadedMeshTable plain = loadedMesh(in);
  in.cornerContact = true;
  LoadedMeshTable corner = loadedMesh(in);
  ASSERT_TRUE(plain.failure.empty() && corner.failure.empty()) << plain.failure << corner.failure;
  EXPECT_GT(corner.cornerPositions, 0);
  int firstIn = -1, mismatches = 0;
  for (int i = 0; i < in.positions; ++i) {
    double tau = static_cast<double>(i) / in.positions;
    double approach = plain.te[static_cast<size_t>(i)];
    // The incoming pair stands at (tau - 1) base pitches, the outgoing at tau + 1 (beyond eps).
    double before = (1 - tau) * p, beyond = (tau + 1 - eps) * p;
    bool predicted = (tau > 0 && rig.wheelCorner(before) < approach - 1e-12) ||
                     (beyond > 0 && rig.pinionCorner(beyond) < approach - 1e-12);
    bool seen = corner.te[static_cast<size_t>(i)] < approach - 1e-15;
    mismatches += predicted != seen;
  }
  // The incoming pair's corner: the run of positions with corner contact that ends the period.
  for (int i = in.positions - 1; i > 0 && corner.te[static_cast<size_t>(i)] < plain.te[static_cast<size_t>(i)] - 1e-15;
       --i)
    firstIn = i;
  EXPECT_LE(mismatches, 2) << "positions where corner contact is predicted and not seen, or seen and not predicted";
  // The extra roll before the start: where the corner's separation equals the single pair's
  // approach (it barely changes over these positions).
  ASSERT_GE(firstIn, 0);
  double approach = plain.te[static_cast<size_t>(firstIn)], lo = 0, hi = 0.5 * p;
  for (int k = 0; k < 100; ++k) {
    double mid = 0.5 * (lo + hi);
    (rig.wheelCorner(mid) < approach ? lo : hi) = mid;
  }
  double roll = (1.0 - static_cast<double>(firstIn) / in.positions) * p;
  EXPECT_NEAR(roll, lo, p / in.positions)
      << "extra roll angle " << lo / in.g.rb1 * 180 / M_PI << " deg at an approach of " << approach * 1e6 << " um";
  EXPECT_GT(lo / p, 0.02); // a real extension of the path, not a rounding
}

// Long relief of more than the load's deflection takes the corners out of contact.
TEST(CornerContact, LongReliefRemovesIt) {
  LoadedMeshInput in = spur(8000.0);
  in.slices = 1;
  in.positions = 1000;
  in.cornerContact = true;
  EXPECT_GT(loadedMesh(in).cornerPositions, 0) << loadedMesh(in).failure;
  for (int k = 0; k < 2; ++k) {
    in.sep.tipRelief[k] = 25e-6;
    in.sep.reliefLength[k] = std::max(0.0, loadedMesh(in).pathLength - in.g.basePitch);
  }
  LoadedMeshTable t = loadedMesh(in);
  ASSERT_TRUE(t.failure.empty());
  EXPECT_EQ(t.cornerPositions, 0);
}

namespace {

// A spur pair 19/40 whose pinion has one tooth (the sixth) with a pitch deviation e.
struct OneTooth {
  LoadedMeshInput in = pair(19, 40, 4e-3, 0, 0.040, kCPrime, 4000.0);
  double e = 10e-6, cosAlpha = std::cos(20 * M_PI / 180);
  std::vector<double> pitch = std::vector<double>(19, 0.0);
  OneTooth() {
    in.slices = 1;
    in.positions = 32;
    pitch[5] = e;
    in.toothLateness[0] = toothLateness(pitch, cosAlpha);
    in.toothLateness[1].assign(40, 0.0);
  }
};

} // namespace

// Over the hunting period (19 x 40 mesh periods) the pinion's teeth take turns: where one
// pair carries the load alone, the error exceeds the perfect teeth's by exactly that tooth's
// lateness, and the sixth tooth steps it by about e against the fifth.
TEST(PitchDeviations, OneToothStepsTheErrorByItsDeviation) {
  OneTooth c;
  LoadedMeshInput perfect = c.in;
  perfect.toothLateness[0].clear();
  perfect.toothLateness[1].clear();
  LoadedMeshTable t = loadedMesh(c.in), p = loadedMesh(perfect);
  ASSERT_TRUE(t.failure.empty() && p.failure.empty());
  ASSERT_EQ(t.periods, 19 * 40);
  ASSERT_EQ(t.te.size(), static_cast<size_t>(19 * 40 * c.in.positions));
  const auto& late = c.in.toothLateness[0];
  int P = c.in.positions, single = P - 2; // late in the period: one pair alone (eps_alpha 1.63)
  for (int n = 0; n < 19 * 40; ++n) {
    double d = t.te[static_cast<size_t>(n * P + single)] - p.te[static_cast<size_t>(single)];
    EXPECT_NEAR(d, late[static_cast<size_t>(n % 19)], 1e-12) << "mesh period " << n;
  }
  double step = late[5] - late[4];
  EXPECT_NEAR(step, c.e * c.cosAlpha, c.e / 19 + 1e-15);
  EXPECT_NEAR(late[18], 0.0, 1e-18); // the sum closes over the circumference
}

// The spectrum over the hunting period: sidebands at the pinion's shaft orders around each
// mesh order, with the amplitudes of a discrete Fourier transform summed by hand; none at
// the wheel's own orders, which the pinion's error does not repeat with.
TEST(PitchDeviations, SidebandsMatchAHandMadeFourierTransform) {
  OneTooth c;
  LoadedMeshTable t = loadedMesh(c.in);
  ASSERT_TRUE(t.failure.empty());
  OrderSpectrum sp = orderSpectrum(t.te, t.periods);
  const size_t N = t.te.size(), H = static_cast<size_t>(t.periods);
  double mean = 0;
  for (double v : t.te)
    mean += v / static_cast<double>(N);
  auto hand = [&](size_t q) {
    std::complex<double> sum = 0;
    for (size_t n = 0; n < N; ++n)
      sum += (t.te[n] - mean) * std::polar(1.0, -2 * M_PI * static_cast<double>(q * n % N) / static_cast<double>(N));
    return 2.0 * std::abs(sum) / static_cast<double>(N);
  };
  double top = *std::max_element(sp.amplitude.begin(), sp.amplitude.end());
  // Bin q is order q / H of the mesh: the pinion turns once in 40 bins' worth (H / 19), the wheel in 19.
  for (size_t k = 1; k <= 2; ++k)
    for (long m : {-2, -1, 1, 2}) {
      size_t q = static_cast<size_t>(static_cast<long>(k * H) + m * 40);
      EXPECT_NEAR(sp.amplitude[q - 1], hand(q), 1e-9 * top) << "mesh order " << k << ", pinion order " << m;
      EXPECT_GT(sp.amplitude[q - 1], 1e-3 * top) << "mesh order " << k << ", pinion sideband " << m;
    }
  for (size_t q : {H - 19, H + 19, 2 * H + 19}) // the wheel's orders, not the pinion's
    EXPECT_LT(sp.amplitude[q - 1], 1e-9 * top);
  EXPECT_NEAR(sp.harmonic(1), hand(H), 1e-9 * top);
}

// Harris's map: a long relief of the amount the single pair deflects under the design load
// gives its least peak-to-peak near that load, and twice the relief near twice the load.
TEST(LoadedMesh, HarrisMapLeastErrorAtTheReliefsDesignLoad) {
  auto leastAt = [](double relief) {
    double at = 0, least = INFINITY;
    for (int k = 1; k <= 60; ++k) {
      LoadedMeshInput in = spur(250.0 * k);
      in.slices = 1;
      in.positions = 400;
      for (int g = 0; g < 2; ++g) {
        in.sep.tipRelief[g] = relief;
        in.sep.reliefLength[g] = std::max(0.0, loadedMesh(spur(1.0)).pathLength - in.g.basePitch);
      }
      LoadedMeshTable t = loadedMesh(in);
      EXPECT_TRUE(t.failure.empty());
      if (t.peakToPeakTe < least) {
        least = t.peakToPeakTe;
        at = in.load;
      }
    }
    return at;
  };
  // The single pair's deflection at the design load: the load over its stiffness at the
  // path's middle (c' b, the shape's peak 1.0).
  double design = 6000.0, relief = design / (kCPrime * 0.040);
  double one = leastAt(relief), two = leastAt(2 * relief);
  EXPECT_NEAR(one / design, 1.0, 0.3) << "least at " << one << " N";
  EXPECT_NEAR(two / (2 * design), 1.0, 0.3) << "least at " << two << " N";
}

// IEC 61672-1:2013 Table 3, the A-weighting at the exact base-ten frequencies of the
// one-third octaves, to its 0.1 dB; and the turbine's mesh frequency.
TEST(Levels, AWeightingFollowsIec61672) {
  const double table[] = {-70.4, -63.4, -56.7, -50.5, -44.7, -39.4, -34.6, -30.2, -26.2, -22.5, -19.1, -16.1,
                          -13.4, -10.9, -8.6,  -6.6,  -4.8,  -3.2,  -1.9,  -0.8,  0.0,   0.6,   1.0,   1.2,
                          1.3,   1.2,   1.0,   0.5,   -0.1,  -1.1,  -2.5,  -4.3,  -6.6,  -9.3};
  for (int n = -20; n <= 13; ++n) {
    double f = 1000.0 * std::pow(10.0, n / 10.0);
    EXPECT_NEAR(aWeighting(f), table[n + 20], 0.051) << f << " Hz";
  }
  EXPECT_NEAR(aWeighting(1000.0), 0.0, 1e-3);
  // 33 teeth at 9364 rpm mesh at 5150 Hz, where A adds about half a decibel.
  EXPECT_NEAR(aWeighting(33 * 9364 / 60.0), 0.45, 0.1);
}

// A level is the RMS of the order against its reference: 1 um of amplitude against 1 pm.
TEST(Levels, LevelOfAnOrderIsItsRmsInDecibels) {
  EXPECT_NEAR(levelOf(1e-6, 1e-12), 20 * std::log10(1e6 / std::sqrt(2.0)), 1e-12);
  std::vector<double> v;
  for (int i = 0; i < 64 * 3; ++i)
    v.push_back(2.0 + 0.5 * std::sin(2 * M_PI * i / 64.0) + 0.25 * std::cos(4 * M_PI * i / 64.0));
  OrderSpectrum s = orderSpectrum(v, 3);
  EXPECT_NEAR(s.harmonic(1), 0.5, 1e-12);
  EXPECT_NEAR(s.harmonic(2), 0.25, 1e-12);
  EXPECT_NEAR(s.total(1.0), 10 * std::log10(0.5 * (0.25 + 0.0625)), 1e-12);
}

namespace {

// A spur pair with perfect teeth, no relief and no corner contact, and its load sweep; a
// variant with relief and the sweep against it in lines and in dB.
const char* kLoadSweep = R"(
gearbox Plain {
  stage hs: spur { pinion.z = 20;  wheel.z = 40;  normal_module = 4 mm;  face_width = 40 mm;  pressure_angle = 20 deg; }
  operating { input_speed = 1500 rpm; input_torque = TORQUE; }
  scene te on hs {
    effects { loaded_mesh { slices = 1; positions = 400; } }
    output peak_to_peak(static_transmission_error), mean(static_transmission_error), harmonic(static_transmission_error, 1),
           level_a(static_transmission_error), mean(stiffness);
  }
  study load { sweep input_torque in 20 N*m..1220 N*m step 300 N*m; output te.peak_to_peak(static_transmission_error),
               te.mean(static_transmission_error), te.harmonic(static_transmission_error, 1), te.mean(stiffness); }
}
gearbox Relieved extends Plain {
  modify hs { tip_relief = 15 um; }
  study map {
    sweep input_torque in 20 N*m..1220 N*m step 300 N*m;
    hs.tip_relief in {0 um, 15 um};
    output te.peak_to_peak(static_transmission_error), relative(te.level_a(static_transmission_error));
  }
}
)";

std::string withTorque(double newtonMetres) {
  std::string s = kLoadSweep;
  s.replace(s.find("TORQUE"), 6, fmt::format("{} N*m", newtonMetres));
  return s;
}

// A scene's number at the spec's operating point.
double sceneNumber(const gbx::test::Fixture& f, const std::string& key) {
  gbx::rt::dyn::SceneResult r = gbx::rt::dyn::runScene(*f.model, *f.design, f.scene("te"));
  EXPECT_TRUE(r.failure.empty()) << r.failure;
  const auto* n = r.find(key);
  return n ? n->value : NAN;
}

} // namespace

// The load sweep's transmission error at each load is the loaded mesh solved at that load
// as the operating point, to 1e-9.
TEST(LoadSweep, EachPointIsTheLoadedMeshAtThatLoad) {
  auto f = gbx::test::compile("load.gbx", withTorque(400), "Plain");
  gbx::rt::SweepStudy s = gbx::rt::sweep(*f.model, *f.design, f.study("load"));
  ASSERT_TRUE(s.failure.empty()) << s.failure;
  ASSERT_EQ(s.points.size(), 5u);
  const char* keys[] = {"peak_to_peak(static_transmission_error)", "mean(static_transmission_error)",
                        "harmonic(static_transmission_error, 1)", "mean(stiffness)"};
  for (const auto& p : s.points) {
    auto at = gbx::test::compile("load.gbx", withTorque(p.x), "Plain");
    for (size_t i = 0; i < 4; ++i) {
      double single = sceneNumber(at, keys[i]);
      EXPECT_NEAR(p.y[i], single, 1e-9 * std::fabs(single)) << keys[i] << " at " << p.x << " N*m";
    }
  }
  // The mean approach grows with the load; perfect teeth without relief keep every pair on
  // the path in contact at any load, so the mean stiffness does not change; a static scene
  // has no stability.
  EXPECT_GT(s.points.back().y[1], 10 * s.points.front().y[1]);
  EXPECT_NEAR(s.points.back().y[3], s.points.front().y[3], 1e-12 * s.points.front().y[3]);
  EXPECT_TRUE(std::isnan(s.points.front().stability));
}

// A set of lines beside the sweep: the sweep once per value; `relative` of a level reads the
// baseline at the same load and line, so where both carry the same relief it is 0 dB and
// otherwise the difference of the two levels.
TEST(LoadSweep, LinesAndRelativeLevelsReadTheBaselineAtTheSamePoint) {
  auto f = gbx::test::compile("load.gbx", withTorque(400), "Relieved");
  auto base = gbx::test::compile("load.gbx", withTorque(400), "Plain");
  gbx::rt::SweepStudy s = gbx::rt::sweep(*f.model, *f.design, f.study("map"), base.model.get(), base.design.get());
  ASSERT_TRUE(s.failure.empty()) << s.failure;
  ASSERT_EQ(s.points.size(), 10u);
  EXPECT_EQ(s.seriesTarget, "hs.tip_relief");
  for (size_t k = 0; k < s.points.size(); ++k) {
    const auto& p = s.points[k];
    EXPECT_DOUBLE_EQ(p.series, k < 5 ? 0.0 : 15e-6);
    EXPECT_NEAR(p.y[1], 0.0, 1e-12) << "the baseline carries the line's relief too";
  }
  // Relief of 15 um: least peak-to-peak at a middle load, not at the lightest (Harris).
  double light = s.points[5].y[0], middle = std::min(s.points[6].y[0], s.points[7].y[0]);
  EXPECT_LT(middle, 0.5 * light);
  // Without the lines, the variant's relief against the plain pair: a level difference in dB.
  gbx::rt::SweepStudy plain = gbx::rt::sweep(*f.model, *f.design, f.study("map"), nullptr, nullptr);
  EXPECT_TRUE(std::isnan(plain.points[0].y[1])) << "no baseline, no relative";
}

// Report columns of a scene's orders read each its own order: the column of order 2 is not
// order 1's, nor the level of every order together.
TEST(LoadSweep, ReportColumnsReadTheirOwnOrder) {
  std::string spec = withTorque(400);
  spec.insert(
      spec.find("  study load"),
      "  report { columns te.harmonic(static_transmission_error, 1), te.level_a(static_transmission_error); }\n");
  auto f = gbx::test::compile("load.gbx", spec, "Plain");
  gbx::rt::dyn::SceneResult r = gbx::rt::dyn::runScene(*f.model, *f.design, f.scene("te"));
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  std::filesystem::path file = std::filesystem::temp_directory_path() / fmt::format("gbxc-orders-{}.gbx", ::getpid());
  std::ofstream(file) << spec;
  std::ostringstream out, err;
  ASSERT_EQ(gbx::driver::run(
                {"solve", "--format", "csv", "--no-timings", "--quiet", "--gearbox", "Plain", file.string()}, out, err),
            0)
      << err.str();
  std::filesystem::remove(file);
  std::string csv = out.str();
  std::string second = csv.substr(csv.find('\n') + 1);
  double harmonic = r.find("harmonic(static_transmission_error, 1)")->value * 1e6;
  double level = r.find("level_a(static_transmission_error)")->value;
  EXPECT_NE(second.find(fmt::format("{:.6g}", harmonic).substr(0, 6)), std::string::npos) << csv;
  EXPECT_NE(second.find(fmt::format("{:.6g}", level).substr(0, 6)), std::string::npos) << csv;
}
