#pragma once
// The Levenberg-Marquardt loop of thesis 2.2.2 (eq. 2.58-2.65, Madsen/Nielsen/Tingleff), written
// once for any number of parameters: the pose fit (6, detect/pose_fit.cpp) and the model
// learning fit (pose, size, shape and taper, detect/model_learning_fit.cpp) both run it. The
// caller supplies the linearisation (cost 0.5 sum r^2, J^T J and J^T r) at a state and the step
// x <- x (+) h, so states on a manifold (rotations) and bounded parameters stay the caller's
// business. N may be Eigen::Dynamic when the count is known only at run time (the stripe
// calibration's cameras); the linearisation is then made with its size.

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

enum class LmStop { kGradient, kStep, kMaxIterations };

// A state's parameters, a step h or a residual's Jacobian row: N values.
template <int N>
using LmVector = Eigen::Matrix<double, N, 1>;

template <int N>
struct LmLinearisation {
  LmLinearisation() : LmLinearisation(N == Eigen::Dynamic ? 0 : N) {}
  explicit LmLinearisation(Eigen::Index n)
      : jtj(Eigen::Matrix<double, N, N>::Zero(n, n)), g(LmVector<N>::Zero(n)) {}
  double cost = 0.0;  // 0.5 sum r^2 (eq. 2.49)
  Eigen::Matrix<double, N, N> jtj;
  LmVector<N> g;  // J^T r
};

// Sums many residuals' rows into a linearisation: rows are kept in a block of kRows and added
// to J^T J and J^T r as one matrix product per block, which costs a fraction of one outer
// product per row (and far less again in a build without inlining, e.g. under sanitizers).
// Fixed N only; take() adds the last block and gives the sum.
template <int N>
class LmRowSum {
 public:
  static constexpr int kRows = 64;

  void add(const LmVector<N>& j, double r) {
    rows_.col(used_) = j;
    r_[used_] = r;
    lin_.cost += 0.5 * r * r;
    if (++used_ == kRows) flush();
  }
  LmLinearisation<N> take() {
    flush();
    return lin_;
  }

 private:
  void flush() {
    if (used_ == 0) return;
    const auto J = rows_.leftCols(used_);
    lin_.jtj.noalias() += J * J.transpose();
    lin_.g.noalias() += J * r_.head(used_);
    used_ = 0;
  }

  LmLinearisation<N> lin_;
  Eigen::Matrix<double, N, kRows> rows_;
  Eigen::Matrix<double, kRows, 1> r_;
  int used_ = 0;
};

template <int N, class State>
struct LmOutcome {
  State x;
  LmLinearisation<N> lin;     // at x
  double initial_cost = 0.0;  // 0.5 sum r^2 at the initial state
  int iterations = 0;
  LmStop stop = LmStop::kMaxIterations;
};

// linearise(State) -> LmLinearisation<N>; step(State, h) -> State; scale(State) -> double, the
// size of the state the step tolerance is relative to (eq. 2.64: ||h|| <= eps'' (||x|| + eps'')).
template <int N, class State, class Linearise, class Step, class Scale>
LmOutcome<N, State> levenberg_marquardt(const State& initial, const LmOptions& options,
                                        Linearise&& linearise, Step&& step, Scale&& scale) {
  using Vector = LmVector<N>;
  LmOutcome<N, State> out{initial, linearise(initial)};
  LmLinearisation<N>& lin = out.lin;
  out.initial_cost = lin.cost;
  double mu = options.tau * lin.jtj.diagonal().maxCoeff();  // eq. 2.60
  if (!(mu > 0.0)) mu = options.tau;
  double nu = 2.0;
  out.stop = LmStop::kMaxIterations;
  int k = 0;
  for (; k < options.max_iterations; ++k) {
    if (lin.g.template lpNorm<Eigen::Infinity>() <= options.gradient_tolerance) {  // eq. 2.63
      out.stop = LmStop::kGradient;
      break;
    }
    Eigen::Matrix<double, N, N> a = lin.jtj;
    a.diagonal().array() += mu;
    const Vector h = a.ldlt().solve(-lin.g);  // eq. 2.58
    const double x_norm = scale(out.x);
    if (!h.allFinite() ||
        h.norm() <= options.step_tolerance * (x_norm + options.step_tolerance)) {  // eq. 2.64
      out.stop = LmStop::kStep;
      break;
    }
    State x_new = step(out.x, h);
    LmLinearisation<N> lin_new = linearise(x_new);
    const double predicted = 0.5 * h.dot(mu * h - lin.g);      // eq. 2.62
    const double rho = (lin.cost - lin_new.cost) / predicted;  // eq. 2.61
    if (predicted > 0.0 && rho > 0.0 && std::isfinite(lin_new.cost)) {
      out.x = std::move(x_new);
      lin = lin_new;
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
