// Standalone check of ScuffingReference.h on the NREL 5 MW high-speed stage (docs/rating.md).
// Build: g++ -std=c++20 -O2 -Wall -Wextra -o build-ref/check tests/unit/rating/ScuffingReferenceCheck.cpp
// Prints every intermediate beside the value a commercial program (KISSsoft 03/2017, ISO/TR 13989:2000,
// ISO/TR 15144-1:2014) printed, the relative difference, and the TS edition's value with TS - TR.
#include <cmath>
#include <cstdio>

#include "ScuffingReference.h"

using namespace gbx::refscuff;

static Pair nrel() {
  Pair p{};
  p.z1 = 24; p.z2 = 95; p.mn = 14; p.beta_deg = 10; p.alpha_n_deg = 20; p.a = 861; p.b = 360;
  p.x1 = 0.48; p.x2 = 0.6691; p.da1 = 380.747; p.da2 = 1395.376;
  p.E1 = p.E2 = 206000; p.nu1 = p.nu2 = 0.3;
  // Case-carburised steel, TR 13989-2 clause 5.3: lambda_M = 50 W/(m K), rho c = 3.8 N/(mm^2 K)
  // (=> X_M = 50.0, the TR's value for steel). The struct defaults (45, 7830, 440) give X_M = 55.4.
  p.lambdaM1 = p.lambdaM2 = 50; p.rho1 = p.rho2 = 7830; p.cM1 = p.cM2 = 3.8e6 / 7830;
  p.Ra1 = p.Ra2 = 0.6; p.Ca1 = p.Ca2 = 2;
  p.T1 = 40953; p.n1 = 1165.9;
  p.KA = 1.25; p.Kv = 1.092; p.KHb = 1.150; p.KHa = 1.069; p.KBg = 1.274;
  p.Xmp = 1; p.lubrication = 0;
  p.nu40 = 220; p.nu100 = 19; p.rho15 = 890; p.theta_oil = 80; p.mineral = true;
  p.fzgLoadStage = 14; p.fvaLoadStage = 10; p.WW = 1;
  return p;
}

static int misses = 0;
static void row(const char* name, double tr, double pub, double ts, bool count = true) {
  if (std::isnan(pub)) {
    std::printf("  %-28s %12.4f %12s %8s %12.4f %10.4f\n", name, tr, "-", "", ts, ts - tr);
    return;
  }
  const double rel = (tr - pub) / pub * 100.0;
  const bool miss = count && std::fabs(rel) > 3.0;
  if (miss) ++misses;
  std::printf("  %-28s %12.4f %12.4f %+7.2f%%%s %12.4f %10.4f\n", name, tr, pub, rel, miss ? "!" : " ", ts,
              ts - tr);
}

int main() {
  const Pair p = nrel();
  const Result R = rate(p, Edition::TR);
  const Result S = rate(p, Edition::TS);
  const double N = NAN;
  std::printf("NREL 5 MW high-speed stage: TR edition vs published (KISSsoft), TS edition, TS-TR\n");
  std::printf("  %-28s %12s %12s %8s  %12s %10s\n", "quantity", "TR", "published", "rel", "TS", "TS-TR");
  std::printf(" geometry and loads\n");
  row("alpha_t [deg]", R.alphaT_deg, N, S.alphaT_deg);
  row("alpha_wt [deg]", R.alphaWt_deg, N, S.alphaWt_deg);
  row("beta_b [deg]", R.betaB_deg, N, S.betaB_deg);
  row("v (reference) [m/s]", R.v, N, S.v);
  row("F_t [N]", R.Ft, N, S.Ft);
  row("eps_alpha", R.epsAlpha, N, S.epsAlpha);
  row("eps_beta", R.epsBeta, N, S.epsBeta);
  row("eps_gamma", R.epsGamma, N, S.epsGamma);
  row("K_Bgamma from eps_gamma", helicalLoadFactor(R.epsGamma), 1.274, helicalLoadFactor(S.epsGamma));
  row("eps_1 / pinion addendum", R.eps1, N, S.eps1);
  row("eps_2 / wheel addendum", R.eps2, N, S.eps2);
  row("Gamma_A", R.gammaA, N, S.gammaA);
  row("Gamma_B", R.gammaB, N, S.gammaB);
  row("Gamma_C", 0.0, N, 0.0);
  row("Gamma_D", R.gammaD, N, S.gammaD);
  row("Gamma_E", R.gammaE, N, S.gammaE);
  std::printf(" flash temperature (TR 13989-1 / TS 6336-20)\n");
  row("w_Bt [N/mm]", R.wBt, 1119.63, S.wBt);
  row("X_alphabeta", R.XalphaBeta, 1.016, S.XalphaBeta);
  row("X_M", R.XM, 50.058, S.XM);
  row("eta_oil (eta_M) [mPa s]", R.etaM, 30.09, S.etaM);
  row("X_L", R.XL, 0.843, S.XL);
  row("X_R (TS only in mu_m)", R.XR, N, S.XR);
  row("v_SigmaC [m/s]", R.vSigmaC, N, S.vSigmaC);
  row("rho_redC (normal) [mm]", R.rhoRedC, N, S.rhoRedC);
  row("mu_m", R.muM, 0.041, S.muM);
  row("C_eff [um]", R.Ceff, N, S.Ceff);
  row("X_J max", R.XJ_max, N, S.XJ_max);
  row("theta_flm [K]", R.thetaFlm, 30.20, S.thetaFlm);
  row("theta_M [C]", R.thetaM, 94.19, S.thetaM);
  row("theta_S [C]", R.thetaS, 451.98, S.thetaS);
  row("Gamma at theta_Bmax", R.gamma_at_max, 0.529, S.gamma_at_max);
  row("X_Gamma at theta_Bmax", R.XGamma_at_max, 0.889, S.XGamma_at_max);
  row("theta_fla max [K]", R.thetaFlaMax, 169.50 - 94.19, S.thetaFlaMax);
  row("theta_fla at E [K]", R.thetaFlaE, 169.50 - 94.19, S.thetaFlaE);
  row("theta_B max [C]", R.thetaBmax, 169.50, S.thetaBmax);
  row("S_B", R.SB, 4.156, S.SB);
  std::printf(" integral temperature (TR 13989-2 / TS 6336-21)\n");
  row("mu_mC", R.muMC_int, N, S.muMC_int);
  row("X_E", R.XE, N, S.XE);
  row("X_BE", R.XBE, N, S.XBE);
  row("X_Q", R.XQ, N, S.XQ);
  row("X_Ca", R.XCa_int, N, S.XCa_int);
  row("X_eps", R.XEps, N, S.XEps);
  row("theta_flaE [K]", R.thetaFlaE_int, N, S.thetaFlaE_int);
  row("theta_flaint [K]", R.thetaFlaInt, 16.25, S.thetaFlaInt);
  row("theta_M (integral) [C]", R.thetaM_int, N, S.thetaM_int);
  row("theta_int [C]", R.thetaInt, 115.75, S.thetaInt);
  row("theta_MT [C]", R.thetaMT, N, S.thetaMT);
  row("theta_flaintT [K]", R.thetaFlaIntT, N, S.thetaFlaIntT);
  row("theta_intS [C]", R.thetaIntS, 455.17, S.thetaIntS);
  row("S_intS", R.SintS, 3.932, S.SintS);
  std::printf(" micropitting (TR 15144-1 / TS 6336-22, method B)\n");
  row("mu_m", R.muM_mp, 0.030, S.muM_mp);
  row("H_V", R.HV, N, S.HV);
  row("X_Ca", R.XCa_mp, N, S.XCa_mp);
  row("theta_M [C]", R.thetaM_mp, 85.0, S.thetaM_mp);
  static const char* nm[7] = {"A", "AB", "B", "C", "D", "DE", "E"};
  for (int i = 0; i < 7; ++i) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "lambda_GF at %s", nm[i]);
    row(buf, R.lambdaPoints[i], i == 0 ? 1.053 : N, S.lambdaPoints[i]);
  }
  std::printf("  lambda_GF,min at point %s (TR) / %s (TS); published: A\n", R.lambdaMinAt.c_str(),
              S.lambdaMinAt.c_str());
  row("lambda_GF,min", R.lambdaGFmin, 1.053, S.lambdaGFmin);
  row("theta_M of FVA test [C]", R.thetaM_test, N, S.thetaM_test);
  row("lambda_GFT", R.lambdaGFT, 0.102, S.lambdaGFT);
  row("lambda_GFP", R.lambdaGFP, 0.143, S.lambdaGFP);
  row("S_lambda", R.Slambda, 7.360, S.Slambda);

  // Gamma grid at the named points; the flash temperature at C must be exactly zero.
  std::printf("\nnamed points (TR): Gamma, y [mm], rho_n [mm], v_g [m/s], X_Gamma, X_J, theta_fla [K], lambda\n");
  bool cZero = false;
  for (const PathPoint& q : R.path)
    if (!q.name.empty()) {
      std::printf("  %-3s %9.5f %9.3f %9.3f %8.4f %8.5f %7.4f %9.4f %8.4f\n", q.name.c_str(), q.gamma, q.y,
                  q.rho_rel, q.vg, q.XGamma, q.XJ, q.theta_fla, q.lambda);
      if (q.name == "C") cZero = (q.theta_fla == 0.0);
    }
  std::printf("  path points: %zu; theta_fla at C == 0 exactly: %s\n", R.path.size(), cZero ? "yes" : "NO");

  // Cross-check of the factor form (A.5) against Blok's formula at E (same mu, X_Gamma, X_J = 1).
  {
    const Geo g = geometry(p);
    const double G = g.gE, Er = R.Er;
    const double wn = R.XGamma_at_max * R.wBt / std::cos(g.at);
    const double blok = flashTemperatureBlok(R.muM, wn, g.vr1(G), g.vr2(G), g.rhoN(G), Er, R.BM1, R.BM2);
    std::printf("\nflash at E: factor form %.4f K, Blok form %.4f K (ratio %.5f; 0.51*1.22 vs 1.11(pi/8)^.25/sqrt2)\n",
                R.thetaFlaE, blok, blok / R.thetaFlaE);
  }
  {
    Pair d = p;
    d.lambdaM1 = d.lambdaM2 = 45; d.cM1 = d.cM2 = 440;
    const Result D = rate(d, Edition::TR);
    std::printf("struct-default steel (45 W/mK, 7830, 440): X_M %.3f, theta_B %.2f, S_B %.3f\n", D.XM,
                D.thetaBmax, D.SB);
    Pair w = p;
    w.pinionDrives = false;
    const Result W = rate(w, Edition::TR);
    std::printf("wheel driving (wind-turbine power flow): Gamma_max %.3f, theta_B %.2f, S_B %.3f, X_J max %.4f\n",
                W.gamma_at_max, W.thetaBmax, W.SB, W.XJ_max);
    const double A0 = R.path.front().theta_fla;
    std::printf("pinion driving: theta_fla at A %.4f K (X_J %.4f) vs at E %.4f K; without X_J A/E = %.5f\n",
                A0, R.path.front().XJ, R.thetaFlaE, A0 / R.path.front().XJ / R.thetaFlaE);
  }

  // Doubling T1 with everything else fixed.
  {
    Pair d = p;
    d.T1 *= 2;
    for (Edition e : {Edition::TR, Edition::TS}) {
      const Result a = rate(p, e), b = rate(d, e);
      std::printf("\n%s: T1 x2: theta_fla,max ratio %.5f (at E %.5f; closed form 2^0.95 = %.5f: theta ~ mu w^0.75,"
                  " mu ~ w^0.2, X_J varies with C_eff ~ F_t), S_B %.4f -> %.4f, mu_m %.5f -> %.5f (ratio %.5f = 2^0.2 "
                  "%.5f)\n",
                  e == Edition::TR ? "TR" : "TS", b.thetaFlaMax / a.thetaFlaMax, b.thetaFlaE / a.thetaFlaE,
                  std::pow(2.0, 0.95), a.SB, b.SB, a.muM, b.muM, b.muM / a.muM, std::pow(2.0, 0.2));
    }
  }
  std::printf("\nASTM D341: nu(40) %.4f nu(100) %.4f nu(80) %.4f mm^2/s\n", kinematicViscosityASTM(220, 19, 40),
              kinematicViscosityASTM(220, 19, 100), kinematicViscosityASTM(220, 19, 80));
  std::printf("TR rows outside 3 %%: %d\n", misses);
  return 0;
}
