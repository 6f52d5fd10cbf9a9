// Normal contact by projected conjugate gradients (Polonsky & Keer, Wear 231 (1999) 206-219),
// generalised to per-cell approach weights w, cell areas A and several patches sharing one
// approach. All inner products are area-weighted, <x, y> = sum_k A_k x_k y_k, so that A C is the
// (nearly) symmetric compliance and the load condition reads <w, p> = F.
//
// One iteration, contact set I = {p > 0}:
//   1. delta = <w, d + u>_I / <w, w>_I (prescribed load; the multiplier of <w, p> = F, which is
//      the least-squares fit of d + u against w over I), or the prescribed delta.
//   2. g = d - delta w + u (u = C p kept up to date).
//   3. t = z + beta t_old on I (beta = G / G_old, G = <g, z>_I; beta = 0 after the set grew);
//      under a prescribed load t is projected onto <w, t>_I = 0 so the step keeps the load.
//      Unpreconditioned z = g. Preconditioned (Vollebregt, J. Comput. Phys. 2014) z = R M R g,
//      R the restriction to I and M the operator's approximate inverse (an FFT-sized product):
//      M is exact for the full-grid circulant, so only the edges of I and the grid slow CG
//      down, and the iteration count grows slowly with the grid (unpreconditioned: like the fourth
//      root of the cell count).
//   4. r = C t (the one operator application); tau = <g, t>_I / <r, t>_I.
//   5. p <- p - tau t on I; negative p -> 0; cells outside I with g < 0 get -tau g (PK's rule).
//   6. u <- u - tau r when nothing was projected, otherwise u = C p afresh; under a prescribed
//      load p and u are rescaled so that <w, p> = F exactly.
#include "core/contact/normal_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/numerics/check.h"

namespace railwear {
namespace {

// Upper bound on w allowed for rounding of a unit normal's component.
constexpr double kWeightRoundingSlack = 1e-12;
// Initial guess: fixed-point steps on the contact threshold and the relative change at which
// they stop (the step contracts by about 1/8 per pass on a Hertz-type gap, so 3-4 passes
// usually suffice; the cap bounds the cost when the grid is far larger than the patch).
constexpr int kMaxInitialGuessPasses = 8;
constexpr double kInitialGuessRelChange = 0.05;
// Stagnation guard of the iteration: restart the conjugate directions when the complementarity
// residual has not fallen below kStagnationFactor times its value at the last restart/progress
// within kStagnationWindow iterations. On SPD operators CG gains a factor 2 in well under 30
// iterations (see DISABLED_IterationsVersusGridSize), so this never fires there.
constexpr int kStagnationWindow = 30;
constexpr double kStagnationFactor = 0.5;

// u = C p for the block-diagonal operator; per-block buffers are allocated once.
class BlockOperator {
 public:
  BlockOperator(const std::vector<const InfluenceOperator*>& blocks, int n) : blocks_(blocks) {
    RAILWEAR_CHECK(!blocks_.empty());
    int offset = 0;
    for (const InfluenceOperator* b : blocks_) {
      RAILWEAR_CHECK(b != nullptr);
      RAILWEAR_CHECK(b->size() > 0);
      offsets_.push_back(offset);
      offset += b->size();
    }
    RAILWEAR_CHECK(offset == n);
    if (blocks_.size() > 1) {
      in_.resize(blocks_.size());
      out_.resize(blocks_.size());
      for (size_t b = 0; b < blocks_.size(); ++b) {
        in_[b].resize(blocks_[b]->size());
        out_[b].resize(blocks_[b]->size());
      }
    }
  }

  void Apply(const Eigen::VectorXd& p, Eigen::VectorXd* u) {
    ++applications_;
    if (blocks_.size() == 1) {
      blocks_[0]->Apply(p, u);
      RAILWEAR_CHECK(u->size() == p.size());
      return;
    }
    u->resize(p.size());
    for (size_t b = 0; b < blocks_.size(); ++b) {
      const int m = blocks_[b]->size();
      in_[b] = p.segment(offsets_[b], m);
      blocks_[b]->Apply(in_[b], &out_[b]);
      RAILWEAR_CHECK(out_[b].size() == m);
      u->segment(offsets_[b], m) = out_[b];
    }
  }

  // True when every block has an approximate inverse (probed with a zero vector).
  bool HasPreconditioner() {
    for (size_t b = 0; b < blocks_.size(); ++b) {
      Eigen::VectorXd z;
      if (!blocks_[b]->ApplyPreconditioner(Eigen::VectorXd::Zero(blocks_[b]->size()), &z)) {
        return false;
      }
    }
    return true;
  }

  // z = M r block by block (M = each block's approximate inverse). Only after
  // HasPreconditioner() returned true.
  void Precondition(const Eigen::VectorXd& r, Eigen::VectorXd* z) {
    ++preconditioner_applications_;
    if (blocks_.size() == 1) {
      RAILWEAR_CHECK(blocks_[0]->ApplyPreconditioner(r, z));
      RAILWEAR_CHECK(z->size() == r.size());
      return;
    }
    z->resize(r.size());
    for (size_t b = 0; b < blocks_.size(); ++b) {
      const int m = blocks_[b]->size();
      in_[b] = r.segment(offsets_[b], m);
      RAILWEAR_CHECK(blocks_[b]->ApplyPreconditioner(in_[b], &out_[b]));
      RAILWEAR_CHECK(out_[b].size() == m);
      z->segment(offsets_[b], m) = out_[b];
    }
  }

  int applications() const { return applications_; }
  int preconditioner_applications() const { return preconditioner_applications_; }

 private:
  const std::vector<const InfluenceOperator*>& blocks_;
  std::vector<int> offsets_;
  std::vector<Eigen::VectorXd> in_, out_;
  int applications_ = 0;
  int preconditioner_applications_ = 0;
};

void ValidateProblem(const NormalProblem& problem, const NormalSolverOptions& options) {
  RAILWEAR_CHECK(options.Validate().empty());
  RAILWEAR_CHECK(problem.force_N.has_value() != problem.approach_m.has_value());
  const Eigen::Index n = problem.gap_m.size();
  RAILWEAR_CHECK(n > 0);
  RAILWEAR_CHECK(problem.approach_weight.size() == n);
  RAILWEAR_CHECK(problem.cell_area_m2.size() == n);
  RAILWEAR_CHECK(problem.gap_m.allFinite());
  RAILWEAR_CHECK(problem.approach_weight.allFinite());
  RAILWEAR_CHECK(problem.cell_area_m2.allFinite());
  RAILWEAR_CHECK(problem.approach_weight.minCoeff() > 0.0);
  RAILWEAR_CHECK(problem.approach_weight.maxCoeff() <= 1.0 + kWeightRoundingSlack);
  RAILWEAR_CHECK(problem.cell_area_m2.minCoeff() > 0.0);
  if (problem.force_N) RAILWEAR_CHECK(std::isfinite(*problem.force_N));
  if (problem.approach_m) RAILWEAR_CHECK(std::isfinite(*problem.approach_m));
}

// The solver's working state and its O(n) kernels.
class PkSolver {
 public:
  PkSolver(const NormalProblem& problem, const NormalSolverOptions& options)
      : d_(problem.gap_m),
        w_(problem.approach_weight),
        area_(problem.cell_area_m2),
        options_(options),
        op_(problem.blocks, static_cast<int>(problem.gap_m.size())),
        n_(static_cast<int>(problem.gap_m.size())) {
    p_.setZero(n_);
    u_.setZero(n_);
    g_.setZero(n_);
    t_.setZero(n_);
    r_.setZero(n_);
    min_ratio_ = (d_.array() / w_.array()).minCoeff();
    if (options.preconditioner != CgPreconditioner::kNone) {
      preconditioned_ = op_.HasPreconditioner();
    }
    if (preconditioned_) {
      z_.setZero(n_);
      masked_.setZero(n_);
    }
  }

  double min_ratio() const { return min_ratio_; }

  NormalSolution SolveForLoad(double force_N) {
    force_ = force_N;
    load_control_ = true;
    InitialGuessForLoad();
    return Iterate();
  }

  NormalSolution SolveForApproach(double approach_m) {
    load_control_ = false;
    delta_ = approach_m;
    InitialGuessForApproach();
    return Iterate();
  }

 private:
  double Load() const { return (area_.array() * w_.array() * p_.array()).sum(); }

  // delta = <w, d + u>_I / <w, w>_I over I = {p > 0}; g = d - delta w + u.
  void UpdateGap() {
    if (load_control_) {
      double num = 0.0, den = 0.0;
      for (int k = 0; k < n_; ++k) {
        if (p_[k] > 0.0) {
          num += area_[k] * w_[k] * (d_[k] + u_[k]);
          den += area_[k] * w_[k] * w_[k];
        }
      }
      RAILWEAR_CHECK(den > 0.0);
      delta_ = num / den;
    }
    g_ = d_ - delta_ * w_ + u_;
  }

  // Complementarity residual [m] and the gap scale h [m] of the stopping criterion.
  void Measure(double* residual, double* scale) const {
    double res = 0.0, h = 0.0;
    for (int k = 0; k < n_; ++k) {
      if (p_[k] > 0.0) {
        res = std::max(res, std::abs(g_[k]));
        h = std::max(h, std::abs(delta_ * w_[k] - d_[k]));
      } else {
        res = std::max(res, -g_[k]);
      }
    }
    *residual = res;
    *scale = h;
  }

  // Pressure shape sqrt(theta w - d) on {d < theta w} (exact for Hertz when theta is half-way
  // between first contact and delta); falls back to the first-contact cells.
  void ShapeForThreshold(double theta) {
    for (int k = 0; k < n_; ++k) p_[k] = std::sqrt(std::max(0.0, theta * w_[k] - d_[k]));
    if (!(p_.maxCoeff() > 0.0)) {
      for (int k = 0; k < n_; ++k) p_[k] = (d_[k] / w_[k] <= min_ratio_) ? 1.0 : 0.0;
    }
  }

  void ScaleToLoad() {
    const double s = force_ / Load();
    p_ *= s;
    u_ *= s;
  }

  // Fixed point on the contact threshold theta: shape for theta, scale to F, fit delta,
  // theta <- (first contact + delta)/2. Starts from the median of d/w (a grid ~1.5x the patch
  // has ~45 % of its cells in contact). Leaves p, u = C p consistent and scaled to F.
  void InitialGuessForLoad() {
    Eigen::VectorXd ratio = d_.array() / w_.array();
    std::nth_element(ratio.data(), ratio.data() + n_ / 2, ratio.data() + n_);
    double theta = ratio[n_ / 2];
    for (int pass = 0; pass < kMaxInitialGuessPasses; ++pass) {
      ShapeForThreshold(theta);
      op_.Apply(p_, &u_);
      ScaleToLoad();
      UpdateGap();
      const double next = 0.5 * (min_ratio_ + delta_);
      const double change = std::abs(next - theta);
      theta = next;
      if (change <= kInitialGuessRelChange * std::abs(theta - min_ratio_)) break;
    }
  }

  // Shape for theta = (first contact + delta)/2, scaled to minimise the energy
  // 1/2 <p, C p> + <p, d - delta w> along it.
  void InitialGuessForApproach() {
    ShapeForThreshold(0.5 * (min_ratio_ + delta_));
    op_.Apply(p_, &u_);
    double num = 0.0, den = 0.0;
    for (int k = 0; k < n_; ++k) {
      num += area_[k] * p_[k] * (delta_ * w_[k] - d_[k]);
      den += area_[k] * p_[k] * u_[k];
    }
    const double alpha = (den > 0.0 && num > 0.0) ? num / den : 0.0;
    p_ *= alpha;
    u_ *= alpha;
  }

  NormalSolution Iterate() {
    NormalSolution out;
    const double tol = options_.tolerance;
    bool u_fresh = true;  // u was computed as C p (not updated) since p last changed
    bool reset = true;    // next direction is steepest descent
    double g_old = 0.0;
    int it = 0;
    std::string failure;
    double residual = 0.0, scale = 0.0;
    double best = std::numeric_limits<double>::infinity();
    int since_best = 0;
    for (;;) {
      if (!(Load() > 0.0)) {
        // A step projected every cell away (possible under a prescribed approach): restart
        // from the initial guess, which always carries pressure.
        if (load_control_) {
          InitialGuessForLoad();
        } else {
          InitialGuessForApproach();
        }
        u_fresh = true;
        reset = true;
      }
      UpdateGap();
      Measure(&residual, &scale);
      if (residual <= tol * scale) {
        if (u_fresh) break;
        op_.Apply(p_, &u_);  // confirm with an exact C p before accepting
        if (load_control_) ScaleToLoad();
        u_fresh = true;
        continue;
      }
      if (it >= options_.max_iterations) {
        failure = "no convergence";
        break;
      }
      ++it;
      // Stagnation guard: when the relative residual has not halved within a window, drop the
      // conjugacy (it is lost on operators that are only nearly symmetric) and restart from
      // steepest descent.
      if (residual < kStagnationFactor * best) {
        best = residual;
        since_best = 0;
      } else if (++since_best >= kStagnationWindow) {
        reset = true;
        best = residual;
        since_best = 0;
      }

      // Direction on the contact set: t = z + beta t_old, z = g (plain) or the preconditioned
      // residual, G = <g, z>_I.
      double G = 0.0;
      if (preconditioned_) {
        G = PreconditionedResidual();
      } else {
        for (int k = 0; k < n_; ++k) {
          if (p_[k] > 0.0) G += area_[k] * g_[k] * g_[k];
        }
      }
      const Eigen::VectorXd& z = preconditioned_ ? z_ : g_;
      const double beta = (reset || g_old <= 0.0) ? 0.0 : G / g_old;
      double tw = 0.0, ww = 0.0;
      for (int k = 0; k < n_; ++k) {
        if (p_[k] > 0.0) {
          t_[k] = z[k] + beta * t_[k];
          tw += area_[k] * t_[k] * w_[k];
          ww += area_[k] * w_[k] * w_[k];
        } else {
          t_[k] = 0.0;
        }
      }
      if (load_control_ && ww > 0.0) {
        const double c = tw / ww;
        for (int k = 0; k < n_; ++k) {
          if (p_[k] > 0.0) t_[k] -= c * w_[k];
        }
      }
      g_old = G;

      op_.Apply(t_, &r_);
      double gt = 0.0, rt = 0.0;
      for (int k = 0; k < n_; ++k) {
        if (p_[k] > 0.0) {
          gt += area_[k] * g_[k] * t_[k];
          rt += area_[k] * r_[k] * t_[k];
        }
      }
      if (!(rt > 0.0) || !std::isfinite(gt)) {
        if (beta != 0.0) {  // lost conjugacy (nearly symmetric operator): restart
          reset = true;
          continue;
        }
        failure = "operator not positive on the contact set";
        break;
      }
      const double tau = gt / rt;

      // Step, projection onto p >= 0, and PK's rule for overlapping cells outside the set.
      bool projected = false, grew = false;
      for (int k = 0; k < n_; ++k) {
        if (p_[k] > 0.0) {
          p_[k] -= tau * t_[k];
          if (p_[k] <= 0.0) {
            p_[k] = 0.0;
            projected = true;
          }
        } else if (g_[k] < 0.0 && tau > 0.0) {
          p_[k] = -tau * g_[k];
          grew = true;
        }
      }
      if (projected || grew) {
        op_.Apply(p_, &u_);
        u_fresh = true;
      } else {
        u_ -= tau * r_;
        u_fresh = false;
      }
      reset = grew;
      if (load_control_ && Load() > 0.0) ScaleToLoad();
    }

    out.iterations = it;
    out.pressure_Pa = p_;
    out.approach_m = delta_;
    out.force_N = Load();
    UpdateGap();
    Measure(&residual, &scale);
    out.deformed_gap_m = g_;
    out.complementarity_residual_m = residual;
    out.load_error_relative = load_control_ ? std::abs(out.force_N - force_) / force_ : 0.0;
    out.operator_applications = op_.applications();
    out.preconditioner_applications = op_.preconditioner_applications();
    out.preconditioned = preconditioned_;
    const bool converged =
        failure.empty() && residual <= tol * scale && out.load_error_relative <= tol;
    std::ostringstream msg;
    if (converged) {
      out.status = SolverStatus::kConverged;
      msg << "converged in " << it << " iterations, complementarity residual " << residual
          << " m (gap scale " << scale << " m)";
    } else {
      out.status = SolverStatus::kNotConverged;
      msg << (failure.empty() ? "no convergence" : failure) << " after " << it
          << " iterations: complementarity residual " << residual << " m > tolerance " << tol
          << " x gap scale " << scale << " m";
    }
    out.message = msg.str();
    return out;
  }

  // z = R M R g with R the restriction to I = {p > 0} and M the blocks' approximate inverse
  // (Vollebregt's scheme); returns G = <g, z>_I (>= 0: R M R is positive semidefinite). Under a
  // prescribed load, the caller's projection of t onto <w, t>_I = 0 (orthogonal, area-weighted;
  // P below) completes the preconditioner to P R M R P, still symmetric positive semidefinite:
  // g = P g already (delta is the fit of d + u against w over I, so <w, g>_I = 0), and
  // <g, P z>_I = <g, z>_I. (Projecting along R M R w instead, exact for M = C^-1, saved no
  // iterations on the half-space benchmark and costs a preconditioner application each time the
  // contact set changes.)
  double PreconditionedResidual() {
    for (int k = 0; k < n_; ++k) masked_[k] = p_[k] > 0.0 ? g_[k] : 0.0;
    op_.Precondition(masked_, &z_);
    double G = 0.0;
    for (int k = 0; k < n_; ++k) {
      if (p_[k] > 0.0) {
        G += area_[k] * g_[k] * z_[k];
      } else {
        z_[k] = 0.0;
      }
    }
    return G;
  }

  const Eigen::VectorXd& d_;
  const Eigen::VectorXd& w_;
  const Eigen::VectorXd& area_;
  const NormalSolverOptions& options_;
  BlockOperator op_;
  const int n_;
  Eigen::VectorXd p_, u_, g_, t_, r_;
  // Preconditioning (PreconditionedResidual): the direction's first term z and a masked input.
  bool preconditioned_ = false;
  Eigen::VectorXd z_, masked_;
  double min_ratio_ = 0.0;
  double delta_ = 0.0;
  double force_ = 0.0;
  bool load_control_ = true;
};

NormalSolution NoContact(const NormalProblem& problem, double approach_m, std::string message) {
  NormalSolution out;
  out.status = SolverStatus::kNoContact;
  out.message = std::move(message);
  const Eigen::Index n = problem.gap_m.size();
  out.pressure_Pa.setZero(n);
  out.approach_m = approach_m;
  out.deformed_gap_m = problem.gap_m - approach_m * problem.approach_weight;
  return out;
}

}  // namespace

std::string_view ToString(SolverStatus s) {
  switch (s) {
    case SolverStatus::kConverged:
      return "converged";
    case SolverStatus::kNotConverged:
      return "not converged";
    case SolverStatus::kNoContact:
      return "no contact";
  }
  return "unknown";
}

std::string_view ToString(CgPreconditioner p) {
  switch (p) {
    case CgPreconditioner::kAuto:
      return "auto";
    case CgPreconditioner::kNone:
      return "none";
    case CgPreconditioner::kInverseOperator:
      return "inverse-operator";
  }
  return "unknown";
}

std::string NormalSolverOptions::Validate() const {
  std::ostringstream msg;
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    msg << "tolerance must be > 0 and finite, got " << tolerance;
  } else if (max_iterations < 1) {
    msg << "max_iterations must be >= 1, got " << max_iterations;
  }
  return msg.str();
}

NormalSolution SolveNormal(const NormalProblem& problem, const NormalSolverOptions& options) {
  ValidateProblem(problem, options);
  const double min_ratio = (problem.gap_m.array() / problem.approach_weight.array()).minCoeff();
  if (problem.force_N) {
    if (*problem.force_N <= 0.0) {
      std::ostringstream msg;
      msg << "no contact: prescribed load " << *problem.force_N << " N <= 0";
      return NoContact(problem, min_ratio, msg.str());
    }
    PkSolver solver(problem, options);
    return solver.SolveForLoad(*problem.force_N);
  }
  const double delta = *problem.approach_m;
  if (delta <= min_ratio) {
    std::ostringstream msg;
    msg << "no contact: prescribed approach " << delta
        << " m does not reach the smallest gap (min d/w = " << min_ratio << " m)";
    return NoContact(problem, delta, msg.str());
  }
  PkSolver solver(problem, options);
  return solver.SolveForApproach(delta);
}

}  // namespace railwear
