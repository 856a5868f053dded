#pragma once
// One group of a design's continuous freedoms decided: the point of their box where every
// rule holds that ranks best (docs/language.md, "Continuous freedoms"). One freedom is
// decided by bracketing: samples over the range, the rules' boundaries between them found
// as roots (GSL's Brent), the objective's interior minima by GSL's Brent minimiser. Several
// are decided by NLopt's SLSQP from the best points of a sample of the box, the rules as
// inequality constraints on their margins. Either way the point is then rounded to the
// digits the report prints, in the direction that keeps every rule.
#include <vector>

#include "optimise/Decide.h"

namespace gbx::rt {

struct FreedomGroup;

class Decider {
public:
  Decider(const Evaluator& ev, const std::vector<int>& choice, const FreedomGroup& g);
  DecidedPoint run();

  // One evaluated point of the box, in coordinates normalised to [0, 1] per freedom.
  struct Point {
    std::vector<double> t, x;
    bool feasible = false;
    double violation = INFINITY;
    std::vector<double> keys;    // the objectives (minimised); empty without any
    double objective = INFINITY; // the scalar the optimisers minimise
    std::vector<double> margins; // every rule's, signed (optimise/Violation.h)
    double offCentre = 0;        // squared distance from the middle, normalised
  };
  Point at(const std::vector<double>& t);

private:
  Point atSI(Point p);
  Point alone();
  Point severally();
  Point cell();
  Point towardMiddle(Point p);
  Point boundary(const Point& in, const Point& out, int depth = 0);
  void interiorMinimum(const Point& left, const Point& middle, const Point& right);
  void slsqp(const Point& start);
  Point printed(const Point& p);
  std::string failing(const Point& p);
  void consider(const Point& p);

  const Evaluator& ev_;
  const Model& m_;
  Assignment a_;
  const FreedomGroup& g_;
  std::vector<double> lo_, hi_;
  long evaluations_ = 0;
  Point best_;                        // the best point evaluated so far (none yet: no coordinates)
  std::vector<Point> nearlyFeasible_; // optimisers' end points a rounding away from feasible
  bool flat_ = false;                 // the objectives do not move over the box: the optimiser goes by the middle
};

// Feasible before infeasible; among feasible points the better objectives (12 significant
// digits), then the nearer the middle; among infeasible ones the smaller violation.
bool better(const Decider::Point& p, const Decider::Point& q);

} // namespace gbx::rt
