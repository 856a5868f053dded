#pragma once
// The DIN 743 check cases of two worked solutions, as the reference takes them (mm, N, N·m):
// S2 a shoulder in load case 1, S4 a V-notch in load case 2 with static loads only.
#include "Din743Reference.h"

namespace gbx::test {

// S2: 50CrMo4, shoulder 84/100 r 4, d_eff 100, load case 1, Rz 10 um.
inline Din743Input din743S2Input() {
  Din743Input in;
  in.material = {1100.0, 900.0, Din743SteelGroup::quenched_tempered};
  in.dEff = 100.0;
  in.notch = Din743Shoulder{84.0, 100.0, 4.0};
  in.tensionN = {443341.6, 0.0, 443341.6};
  in.bendingNm = {23275.43, 2909.429, 26184.86};
  in.torsionNm = {13965.26, 0.0, 13965.26};
  in.loadCase = Din743LoadCase::one;
  in.rzUm = 10.0;
  return in;
}

// S4: S235, V-notch 10 mm deep in an 80 mm shaft (root 60), d_eff 80, load case 2, static only.
inline Din743Input din743S4Input() {
  Din743Input in;
  in.material = {360.0, 235.0, Din743SteelGroup::structural};
  in.dEff = 80.0;
  in.notch = Din743VNotch{80.0, 60.0};
  in.tensionN = {40000.0, 0.0, 60000.0};
  in.bendingNm = {12666.667, 0.0, 19000.0};
  in.loadCase = Din743LoadCase::two;
  in.rzUm = 25.0;
  return in;
}

} // namespace gbx::test
