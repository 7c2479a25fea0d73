#pragma once
// Summary of the registration's distortion (issue 8): per-face dilatation K = (1+|mu|)/(1-|mu|)
// (registration.vtp cell data Dilatation) and angle theta = arg(mu) / 2. Eigen in, numbers out.
#include <Eigen/Core>

namespace colonmap::views {

struct DilatationSummary {
  double mean = 0.0, p99 = 0.0, max = 0.0;  // over the finite values
  long faces = 0;                            // finite values counted
  long infinite = 0;                         // non-finite values (|mu| >= 1: folded faces)
};

// p99: the value at rank round(0.99 (n - 1)) of the sorted finite values.
DilatationSummary SummarizeDilatation(const Eigen::VectorXd& K);

// theta = arg(mu) / 2 per face from BeltramiArg (arg mu in (-pi, pi]), in (-pi/2, pi/2].
Eigen::VectorXd DistortionAngle(const Eigen::VectorXd& beltramiArg);

}  // namespace colonmap::views
