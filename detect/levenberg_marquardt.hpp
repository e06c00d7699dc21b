#pragma once
// The Levenberg-Marquardt loop of thesis 2.2.3 (eq. 2.58-2.65, after Madsen/Nielsen/Tingleff),
// once for every fit with a fixed number of parameters: the superquadric pose fit
// (detect/pose_fit.cpp) and the calibrations (calib/). The problem supplies the linearisation at
// a state (cost 0.5 sum r^2, J^T J, g = J^T r) and how a step h moves the state, so rotations can
// be updated by local increments and the loop never sees a parametrisation's singularity.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace rangefit {

struct LmOptions {
  int max_iterations = 20;           // k_max, eq. 2.65
  double tau = 1e-3;                 // mu_0 = tau max_i (J^T J)_ii, eq. 2.60
  double gradient_tolerance = 1e-9;  // eps' on ||g||_inf, eq. 2.63
  double step_tolerance = 1e-7;      // eps'' on the step, eq. 2.64
};

enum class LmTermination {
  kGradient,       // ||g||_inf <= eps' (eq. 2.63)
  kStep,           // small step (eq. 2.64)
  kMaxIterations,  // k >= k_max (eq. 2.65)
};

template <int N>
struct LmLinearisation {
  double cost = 0.0;  // 0.5 sum r^2 (eq. 2.49)
  Eigen::Matrix<double, N, N> jtj = Eigen::Matrix<double, N, N>::Zero();
  Eigen::Matrix<double, N, 1> g = Eigen::Matrix<double, N, 1>::Zero();
};

template <int N, class State>
struct LmOutcome {
  State state;
  LmLinearisation<N> lin;  // at `state` (J^T J gives the covariance of a least-squares fit)
  double initial_cost = 0.0;
  int iterations = 0;
  LmTermination termination = LmTermination::kMaxIterations;
};

// linearise(state) -> LmLinearisation<N>; step(state, h) -> State; size(state) -> double, the
// scale ||x|| of the step test (eq. 2.64).
template <int N, class State, class Linearise, class Step, class Size>
LmOutcome<N, State> levenberg_marquardt(const State& initial, Linearise&& linearise, Step&& step,
                                        Size&& size, const LmOptions& options) {
  using Vector = Eigen::Matrix<double, N, 1>;
  LmOutcome<N, State> out{initial, linearise(initial)};
  out.initial_cost = out.lin.cost;
  double mu = options.tau * out.lin.jtj.diagonal().maxCoeff();  // eq. 2.60
  if (!(mu > 0.0)) mu = options.tau;
  double nu = 2.0;
  int k = 0;
  for (; k < options.max_iterations; ++k) {
    if (out.lin.g.template lpNorm<Eigen::Infinity>() <= options.gradient_tolerance) {  // eq. 2.63
      out.termination = LmTermination::kGradient;
      break;
    }
    Eigen::Matrix<double, N, N> a = out.lin.jtj;
    a.diagonal().array() += mu;
    const Vector h = a.ldlt().solve(-out.lin.g);  // eq. 2.58
    const double x_norm = size(out.state);
    if (!h.allFinite() ||
        h.norm() <= options.step_tolerance * (x_norm + options.step_tolerance)) {  // eq. 2.64
      out.termination = LmTermination::kStep;
      break;
    }
    State next = step(out.state, h);
    LmLinearisation<N> lin_next = linearise(next);
    const double predicted = 0.5 * h.dot(mu * h - out.lin.g);       // eq. 2.62
    const double rho = (out.lin.cost - lin_next.cost) / predicted;  // eq. 2.61
    if (predicted > 0.0 && rho > 0.0 && std::isfinite(lin_next.cost)) {
      out.state = std::move(next);
      out.lin = lin_next;
      mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      nu = 2.0;
    } else {
      mu *= nu;
      nu *= 2.0;
    }
  }
  out.iterations = k;
  return out;
}

}  // namespace rangefit
