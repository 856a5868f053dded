#pragma once
// Independent reference calculation (test oracle) for the ISO 6336-3:2006 (incl. Cor.1:2008)
// method B tooth form factor Y_F and stress correction factor Y_S of an EXTERNAL spur or helical
// gear, evaluated on the virtual spur gear of the normal section.
//
// Unlike the standard (which finds the critical section with its iterative theta equation), the
// root fillet is generated numerically: the trochoid traced by the tip rounding of the basic rack
// of the tool (addendum h_fP*mn, tip radius rho_fP*mn, pressure angle alphaN, profile shift x*mn;
// no protuberance, no grinding stock) is sampled densely, and the critical section is the point
// whose tangent makes 30 deg with the tooth centre line (scan + bisection). The fillet radius
// there is the numerical curvature of the generated curve (circles through three curve points,
// Richardson-extrapolated; no closed-form trochoid curvature is used). The load is applied at the outer point of single pair tooth contact of the
// virtual spur gear (ISO 6336-3 clause 6.2, d_en / alpha_en / gamma_e / alpha_Fen formulas).
//
// Units: all lengths in mm, all angles in radians (except FilletResult::thetaDeg, in degrees).
// Written from first principles; not derived from the gbxc sources.

namespace gbx::testref {

struct FilletGear {
  double z;   // number of teeth (> 0, external)
  double x;   // profile shift coefficient
  double da;  // tip diameter [mm]
};

struct FilletCase {
  FilletGear gear, mate;  // the gear rated, and its mating gear (needed for epsilon_alpha)
  double mn;              // normal module [mm]
  double alphaN;          // normal pressure angle [rad]
  double beta;            // reference helix angle [rad]
  double a;               // working centre distance [mm]
  double haP, hfP, rhoFP; // basic rack of the TOOL in units of mn: h_fP* is the tool addendum,
                          // rho_fP* its tip radius; haP is informational (da is given explicitly)
};

struct FilletResult {
  double sFn;      // tooth root chord at the critical section [mm]
  double hFe;      // bending moment arm, load at outer point of single pair contact [mm]
  double rhoF;     // fillet radius at the critical section [mm]
  double alphaFen; // load direction angle [rad]
  double YF, YS;   // tooth form factor, stress correction factor
  double thetaDeg; // 60 deg + signed roll angle of the virtual gear at which the critical point
                   // is generated; coincides with the theta of ISO 6336-3 eq. for theta
  // extra diagnostics
  double zn, epsAlpha, dEn; // virtual number of teeth, transverse contact ratio, d_en [mm]
};

// samples: number of points along the fillet (from root circle to the involute start).
// Returns NaNs if no 30-degree tangent point is found on the fillet.
FilletResult filletReference(const FilletCase& c, int samples = 40000);

}  // namespace gbx::testref
