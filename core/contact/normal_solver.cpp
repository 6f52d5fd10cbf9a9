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
//
// With a pressure limit p_lim (elastic-perfectly-plastic cells, normal_solver.h) the elastic
// problem is solved first, exactly as above; when its peak stays at or below p_lim that is the
// answer (so a case below the limit is unchanged, bit for bit, at no extra cost). Otherwise the
// same iteration runs on the box 0 <= p <= p_lim, from the elastic pressures clipped: the set I
// above becomes the free set F = {0 < p < p_lim} (the fit of delta, the directions), the plastic
// set P = {p = p_lim} keeps its pressure, the step also projects onto p <= p_lim, and PK's rule
// also releases plastic cells whose gap opens (g > 0: p = p_lim - tau g). These bounded solves
// run unpreconditioned (see SetLimit).
//   - Prescribed approach: one bounded solve.
//   - Prescribed load: restoring the load by a common factor after each step cannot work when
//     the patch must grow (clipped cells lose load that only new cells can carry), so first the
//     approach that carries F is searched with bounded solves under a prescribed approach
//     (secant steps, regula falsi once bracketed, each solve from the last one's pressures) to
//     1e-6 of F; the load-controlled bounded solve then starts from there, restoring the load by
//     "water filling": p <- min(s p, p_lim) on the free cells with s such that <w, p> = F (when
//     every loaded cell is plastic and F is still short, the unloaded cells nearest to contact,
//     smallest (d + u)/w, are loaded to p_lim, the last one with the rest).
#include "core/contact/normal_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

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
// With plastic cells: a load factor on the free cells within this of 1 is rounding (the steps
// keep the load), and u = C p is kept instead of applied afresh.
constexpr double kRoundingFactor = 1e-12;
// The bounded solve under a prescribed load (SolveBoundedForLoad): the search on the approach
// stops within this share of the load, or after this many steps.
constexpr double kApproachLoadTolerance = 1e-6;
constexpr int kMaxApproachSteps = 60;

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

  // True when every block has an approximate inverse (InfluenceOperator::HasPreconditioner).
  bool HasPreconditioner() const {
    return std::all_of(blocks_.begin(), blocks_.end(),
                       [](const InfluenceOperator* b) { return b->HasPreconditioner(); });
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

  // The operator's diagonal, cell by cell [m/Pa].
  Eigen::VectorXd Diagonal() const {
    Eigen::VectorXd d(offsets_.empty() ? 0 : offsets_.back() + blocks_.back()->size());
    for (size_t b = 0; b < blocks_.size(); ++b) {
      for (int k = 0; k < blocks_[b]->size(); ++k) d[offsets_[b] + k] = blocks_[b]->Diagonal(k);
    }
    return d;
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
  if (problem.pressure_limit_Pa) {
    RAILWEAR_CHECK(*problem.pressure_limit_Pa > 0.0 && std::isfinite(*problem.pressure_limit_Pa));
  }
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
        n_(static_cast<int>(problem.gap_m.size())),
        p_lim_(problem.pressure_limit_Pa.value_or(std::numeric_limits<double>::infinity())) {
    p_.setZero(n_);
    u_.setZero(n_);
    g_.setZero(n_);
    t_.setZero(n_);
    r_.setZero(n_);
    min_ratio_ = (d_.array() / w_.array()).minCoeff();
    if (options.preconditioner != CgPreconditioner::kNone) {
      can_precondition_ = op_.HasPreconditioner();
    }
    SetLimit(p_lim_);
    if (can_precondition_) {
      z_.setZero(n_);
      masked_.setZero(n_);
    }
  }

  double min_ratio() const { return min_ratio_; }
  bool grid_full() const { return grid_full_; }

  // The pressure limit of the next solves [Pa] (+inf: none).
  // The bounded solves run unpreconditioned: the restricted inverse R M R mixes the plastic
  // cells' neighbours so that released cells were pushed back over the limit step after step
  // (no convergence on the Hertz cases of the tests), where plain PK converges in tens of
  // iterations.
  void SetLimit(double p_lim) {
    p_lim_ = p_lim;
    preconditioned_ = can_precondition_ && !std::isfinite(p_lim);
    if (std::isfinite(p_lim) && diag_.size() == 0) diag_ = op_.Diagonal();
  }

  // Without `start` from the initial guess; with it from those pressures (clipped to the limit,
  // scaled to the load).
  NormalSolution SolveForLoad(double force_N, const Eigen::VectorXd* start = nullptr) {
    force_ = force_N;
    load_control_ = true;
    if (start == nullptr) {
      InitialGuessForLoad();
    } else {
      p_ = *start;
      ClipToLimit();
      op_.Apply(p_, &u_);
      if (ScaleToLoad()) op_.Apply(p_, &u_);
    }
    return Iterate();
  }

  NormalSolution SolveForApproach(double approach_m, const Eigen::VectorXd* start = nullptr) {
    load_control_ = false;
    delta_ = approach_m;
    if (start == nullptr) {
      InitialGuessForApproach();
    } else {
      p_ = *start;
      ClipToLimit();
      op_.Apply(p_, &u_);
    }
    return Iterate();
  }

  // The bounded problem under a prescribed load F, from the elastic solution `elastic` (whose
  // peak passes the limit): the approach that carries F with p <= p_lim, by secant steps
  // (regula falsi once bracketed) on delta with bounded solves under a prescribed approach, each
  // from the last one's pressures, until the load is within kApproachLoadTolerance; then the
  // load-controlled bounded solve from there makes the load exact. Its active sets are then
  // nearly right, so the load's restoration by water filling moves only a few cells.
  NormalSolution SolveBoundedForLoad(double force_N, double p_lim, const NormalSolution& elastic) {
    SetLimit(p_lim);
    const double x0 = min_ratio_;  // first contact: F(x0) = 0
    double delta = elastic.approach_m;
    Eigen::VectorXd start = elastic.pressure_Pa;
    std::optional<std::pair<double, double>> lo, hi, last;  // (delta, F(delta) - F)
    int side = 0;
    NormalSolution sol;
    int steps = 0;
    for (int step = 0; step < kMaxApproachSteps; ++step) {
      sol = SolveForApproach(delta, &start);
      ++steps;
      if (sol.status != SolverStatus::kConverged) return sol;
      start = sol.pressure_Pa;
      const double e = sol.force_N - force_N;
      if (std::abs(e) <= kApproachLoadTolerance * force_N) break;
      if (e < 0 && sol.plastic_cells == n_) break;  // the whole grid plastic: it cannot carry F
      if (e < 0) {
        if (hi && side == -1) hi->second *= 0.5;  // Illinois
        lo = std::pair{delta, e};
        side = -1;
      } else {
        if (lo && side == +1) lo->second *= 0.5;
        hi = std::pair{delta, e};
        side = +1;
      }
      double next;
      if (lo && hi) {
        next = (lo->first * hi->second - hi->first * lo->second) / (hi->second - lo->second);
        if (!(next > lo->first && next < hi->first)) next = 0.5 * (lo->first + hi->first);
      } else if (last && last->second != e) {
        next = delta - e * (delta - last->first) / (e - last->second);
      } else {
        next = x0 + (delta - x0) * force_N / std::max(sol.force_N, 1e-3 * force_N);
      }
      // Unbracketed secant steps may overshoot: at most doubling the approach from first
      // contact, never back past the lower end.
      if (!hi) next = std::min(next, x0 + 2.0 * (delta - x0));
      if (lo && !(next > lo->first)) next = lo->first + 0.5 * (delta - lo->first);
      last = std::pair{delta, e};
      delta = next;
    }
    if (sol.status != SolverStatus::kConverged) return sol;
    const int search_iterations = total_iterations_;
    NormalSolution out = SolveForLoad(force_N, &start);
    std::ostringstream msg;
    msg << "; pressure limit " << p_lim * 1e-6 << " MPa: " << out.plastic_cells
        << " plastic cells, after " << steps << " solves on the approach (" << search_iterations
        << " iterations with the elastic solve)";
    out.message += msg.str();
    return out;
  }

 private:
  double Load() const { return (area_.array() * w_.array() * p_.array()).sum(); }

  // Free cell: in contact and below the limit (without a limit: in contact).
  bool Free(int k) const { return p_[k] > 0.0 && p_[k] < p_lim_; }

  // delta = <w, d + u>_I / <w, w>_I over I = {p > 0}; g = d - delta w + u.
  void UpdateGap() {
    if (load_control_) {
      double num = 0.0, den = 0.0;
      for (int k = 0; k < n_; ++k) {
        if (Free(k)) {
          num += area_[k] * w_[k] * (d_[k] + u_[k]);
          den += area_[k] * w_[k] * w_[k];
        }
      }
      if (!(den > 0.0)) {  // every loaded cell plastic: fit over all of them
        for (int k = 0; k < n_; ++k) {
          if (p_[k] > 0.0) {
            num += area_[k] * w_[k] * (d_[k] + u_[k]);
            den += area_[k] * w_[k] * w_[k];
          }
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
      if (p_[k] >= p_lim_) {  // plastic: the gap may not open (g <= 0)
        res = std::max(res, g_[k]);
        h = std::max(h, std::abs(delta_ * w_[k] - d_[k]));
      } else if (p_[k] > 0.0) {
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

  // Restores <w, p> = F. Without cells pushed past the limit: p and u scaled by one factor
  // (u stays C p). Otherwise water filling (see the top of the file); returns true when u is no
  // longer C p and must be applied afresh.
  bool ScaleToLoad() {
    const double s = force_ / Load();
    const double p_max = p_.maxCoeff();
    if (!std::isfinite(p_lim_) || (p_max < p_lim_ && s * p_max < p_lim_)) {
      p_ *= s;
      u_ *= s;
      return false;
    }
    return WaterFill();
  }

  // p <- min(s p, p_lim) on the cells below the limit, with the factor s that carries F, the
  // cells at the limit kept there (a uniform factor below 1 would release them all); when every
  // loaded cell reaches the limit and F is still not carried, Grow().
  bool WaterFill() {
    std::vector<char> at_limit(n_);
    for (int k = 0; k < n_; ++k) at_limit[k] = p_[k] >= p_lim_;
    double s = 1.0;
    bool clipped_new = false;
    for (bool first = true;; first = false) {
      double carried = 0.0, free_load = 0.0;
      for (int k = 0; k < n_; ++k) {
        const double a = area_[k] * w_[k];
        if (at_limit[k]) {
          carried += a * p_lim_;
        } else {
          free_load += a * p_[k];
        }
      }
      if (!(free_load > 0.0)) {
        for (int k = 0; k < n_; ++k) {
          if (at_limit[k]) p_[k] = p_lim_;
        }
        if (carried < force_) Grow(force_ - carried);
        return true;
      }
      if (first && !(carried < force_)) {
        // The plastic cells alone carry F or more: every cell scaled down, none at the limit.
        const double f = force_ / Load();
        p_ *= f;
        u_ *= f;
        return false;
      }
      s = (force_ - carried) / free_load;
      bool more = false;
      for (int k = 0; k < n_; ++k) {
        if (!at_limit[k] && s * p_[k] > p_lim_) {
          at_limit[k] = 1;
          more = true;
        }
      }
      if (!more) break;
      clipped_new = true;
    }
    for (int k = 0; k < n_; ++k) p_[k] = at_limit[k] ? p_lim_ : s * p_[k];
    // A factor within rounding of 1 on the free cells alone (the steps keep the load; only
    // rounding moves it) leaves u as good as C p.
    return clipped_new || std::abs(s - 1.0) > kRoundingFactor;
  }

  // Every loaded cell is at the limit and `missing` [N] is not carried: load the unloaded cells
  // nearest to contact under the current displacement (smallest (d + u)/w) to p_lim, the last
  // one with what is left. Sets grid_full_ when the grid's cells run out.
  void Grow(double missing) {
    std::vector<int> order;
    for (int k = 0; k < n_; ++k) {
      if (!(p_[k] > 0.0)) order.push_back(k);
    }
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return (d_[a] + u_[a]) / w_[a] < (d_[b] + u_[b]) / w_[b]; });
    for (int k : order) {
      const double full = area_[k] * w_[k] * p_lim_;
      if (full >= missing) {
        p_[k] = missing / (area_[k] * w_[k]);
        return;
      }
      p_[k] = p_lim_;
      missing -= full;
    }
    grid_full_ = true;
  }

  // Pressures above the limit clipped to it (a guess or a step); true when any was.
  bool ClipToLimit() {
    bool clipped = false;
    for (int k = 0; k < n_; ++k) {
      if (p_[k] > p_lim_) {
        p_[k] = p_lim_;
        clipped = true;
      }
    }
    return clipped;
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
      if (ScaleToLoad()) op_.Apply(p_, &u_);
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
    if (ClipToLimit()) op_.Apply(p_, &u_);
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
    // NormalStopCriterion::kPressureUpdate: the last step's RMS pressure update over the contact
    // set, the RMS pressure there (refreshed as CONTACT does) and whether the sets changed.
    const bool by_update = options_.criterion == NormalStopCriterion::kPressureUpdate;
    double update_rms = std::numeric_limits<double>::infinity(), pressure_rms = 0.0;
    bool sets_changed = true, update_small = false;
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
        sets_changed = true;
      }
      UpdateGap();
      Measure(&residual, &scale);
      if (by_update) {
        update_small = it > 0 && !sets_changed && update_rms <= tol * pressure_rms;
        if (update_small) {
          if (!u_fresh) op_.Apply(p_, &u_);  // the reported gap and residual from an exact C p
          u_fresh = true;
          break;
        }
      } else if (residual <= tol * scale) {
        if (u_fresh) break;
        op_.Apply(p_, &u_);  // confirm with an exact C p before accepting
        if (load_control_ && ScaleToLoad()) op_.Apply(p_, &u_);
        u_fresh = true;
        if (grid_full_) {
          failure = "the load exceeds the pressure limit times the whole grid's area";
          break;
        }
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
          if (Free(k)) G += area_[k] * g_[k] * g_[k];
        }
      }
      const Eigen::VectorXd& z = preconditioned_ ? z_ : g_;
      const double beta = (reset || g_old <= 0.0) ? 0.0 : G / g_old;
      double tw = 0.0, ww = 0.0;
      for (int k = 0; k < n_; ++k) {
        if (Free(k)) {
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
          if (Free(k)) t_[k] -= c * w_[k];
        }
      }
      g_old = G;

      op_.Apply(t_, &r_);
      double gt = 0.0, rt = 0.0;
      for (int k = 0; k < n_; ++k) {
        if (Free(k)) {
          gt += area_[k] * g_[k] * t_[k];
          rt += area_[k] * r_[k] * t_[k];
        }
      }
      double tau = 0.0;
      bool no_direction = false;
      if (!(rt > 0.0) && (t_.array() == 0.0).all()) {
        // No direction: no free cell, or under a prescribed load a single one (its pressure is
        // the load's rest). Only PK's rules below change the sets, at the scale of the
        // operator's diagonal (a cell's own compliance).
        no_direction = true;  // PK's rules below at each cell's own compliance
        // The diagonal is made by SetLimit for a bounded solve only: an elastic solve without a
        // direction read it empty, a segmentation fault (a wheel of 300 mm lateral radius on the
        // edge of a 20 mm groove, half-space model: ApiCrashes.HalfspaceWheelOnAGrooveEdge).
        if (diag_.size() != n_) diag_ = op_.Diagonal();
      } else if (!(rt > 0.0) || !std::isfinite(gt)) {
        if (beta != 0.0) {  // lost conjugacy (nearly symmetric operator): restart
          reset = true;
          continue;
        }
        failure = "operator not positive on the contact set";
        break;
      } else {
        tau = gt / rt;
      }

      // Step, projection onto p >= 0, and PK's rule for overlapping cells outside the set.
      bool projected = false, grew = false;
      double update_sq = 0.0, pressure_sq = 0.0;  // over the free cells, before projecting
      int free_cells = 0;
      for (int k = 0; k < n_; ++k) {
        if (p_[k] >= p_lim_) {
          // A plastic cell whose gap opens is released (PK's rule mirrored; without a
          // direction by the pressure that would close its gap alone, g / C_kk).
          if (g_[k] > 0.0 && (tau > 0.0 || no_direction)) {
            p_[k] = std::max(0.0, p_lim_ - (no_direction ? g_[k] / diag_[k] : tau * g_[k]));
            grew = true;
          }
        } else if (p_[k] > 0.0) {
          p_[k] -= tau * t_[k];
          update_sq += (tau * t_[k]) * (tau * t_[k]);
          pressure_sq += p_[k] * p_[k];
          ++free_cells;
          if (p_[k] <= 0.0) {
            p_[k] = 0.0;
            projected = true;
          } else if (p_[k] >= p_lim_) {
            p_[k] = p_lim_;
            projected = true;
          }
        } else if (g_[k] < 0.0 && tau > 0.0) {
          p_[k] = std::min(p_lim_, -tau * g_[k]);
          grew = true;
        } else if (g_[k] < 0.0 && no_direction) {
          p_[k] = std::min(p_lim_, -g_[k] / diag_[k]);
          grew = true;
        }
      }
      if (by_update) {
        sets_changed = projected || grew;
        update_rms = free_cells > 0 ? std::sqrt(update_sq / free_cells) : 0.0;
        // CONTACT's rms_xk: iterations 1, 2, 3 and every 10th (m_solvpn.f90).
        if (free_cells > 0 && (it <= 3 || it % 10 == 0)) {
          pressure_rms = std::sqrt(pressure_sq / free_cells);
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
      if (load_control_ && Load() > 0.0 && ScaleToLoad()) {
        op_.Apply(p_, &u_);
        u_fresh = true;
        reset = true;
      }
      if (grid_full_) {
        failure = "the load exceeds the pressure limit times the whole grid's area";
        break;
      }
    }

    total_iterations_ += it;
    out.iterations = total_iterations_;
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
    out.load_above_limit = grid_full_;
    for (int k = 0; k < n_; ++k) {
      if (p_[k] >= p_lim_) {
        ++out.plastic_cells;
        out.plastic_force_N += area_[k] * w_[k] * p_[k];
      }
    }
    const bool criterion_met = by_update ? update_small : residual <= tol * scale;
    const bool converged = failure.empty() && criterion_met && out.load_error_relative <= tol;
    std::ostringstream msg;
    if (converged) {
      out.status = SolverStatus::kConverged;
      msg << "converged in " << it << " iterations, complementarity residual " << residual
          << " m (gap scale " << scale << " m)";
      if (by_update) {
        msg << ", last pressure update " << update_rms << " Pa RMS <= tolerance " << tol
            << " x RMS pressure " << pressure_rms << " Pa";
      }
    } else if (by_update) {
      out.status = SolverStatus::kNotConverged;
      msg << (failure.empty() ? "no convergence" : failure) << " after " << it
          << " iterations: last pressure update " << update_rms << " Pa RMS"
          << (sets_changed ? " (contact set still changing)" : "") << ", tolerance " << tol
          << " x RMS pressure " << pressure_rms << " Pa";
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
    for (int k = 0; k < n_; ++k) masked_[k] = Free(k) ? g_[k] : 0.0;
    op_.Precondition(masked_, &z_);
    double G = 0.0;
    for (int k = 0; k < n_; ++k) {
      if (Free(k)) {
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
  bool can_precondition_ = false;  // asked for and every block has an inverse
  bool preconditioned_ = false;    // ... and used by the current solve (not with a limit)
  Eigen::VectorXd z_, masked_;
  double min_ratio_ = 0.0;
  double p_lim_;              // pressure limit [Pa], +inf without one
  Eigen::VectorXd diag_;      // the operator's diagonal C_kk [m/Pa]: with a finite limit, or once
                              // a step has no direction
  int total_iterations_ = 0;  // over every solve of this solver
  bool grid_full_ = false;    // every cell at the limit and the load still not carried
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

std::string_view ToString(NormalStopCriterion c) {
  switch (c) {
    case NormalStopCriterion::kGapResidual:
      return "gap-residual";
    case NormalStopCriterion::kPressureUpdate:
      return "pressure-update";
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

NormalSolverOptions StrictNormalSolverOptions() {
  NormalSolverOptions o;
  o.criterion = NormalStopCriterion::kGapResidual;
  o.tolerance = kStrictNormalTolerance;
  return o;
}

NormalSolution SolveNormal(const NormalProblem& problem, const NormalSolverOptions& options,
                           const Eigen::VectorXd* start) {
  ValidateProblem(problem, options);
  RAILWEAR_CHECK(start == nullptr || (start->size() == problem.gap_m.size() &&
                                       start->allFinite() && start->minCoeff() >= 0.0));
  // A start that carries nothing has no shape to begin from: the initial guess instead.
  if (start != nullptr && !(start->maxCoeff() > 0.0)) start = nullptr;
  const double min_ratio = (problem.gap_m.array() / problem.approach_weight.array()).minCoeff();
  if (problem.force_N) {
    if (*problem.force_N <= 0.0) {
      std::ostringstream msg;
      msg << "no contact: prescribed load " << *problem.force_N << " N <= 0";
      return NoContact(problem, min_ratio, msg.str());
    }
    PkSolver solver(problem, options);
    if (!problem.pressure_limit_Pa) return solver.SolveForLoad(*problem.force_N, start);
    // With a limit: the elastic solve first (unchanged, and the answer when its peak stays
    // below the limit), the bounded one from there.
    solver.SetLimit(std::numeric_limits<double>::infinity());
    NormalSolution elastic = solver.SolveForLoad(*problem.force_N, start);
    if (elastic.status != SolverStatus::kConverged ||
        !(elastic.pressure_Pa.maxCoeff() > *problem.pressure_limit_Pa)) {
      return elastic;
    }
    return solver.SolveBoundedForLoad(*problem.force_N, *problem.pressure_limit_Pa, elastic);
  }
  const double delta = *problem.approach_m;
  if (delta <= min_ratio) {
    std::ostringstream msg;
    msg << "no contact: prescribed approach " << delta
        << " m does not reach the smallest gap (min d/w = " << min_ratio << " m)";
    return NoContact(problem, delta, msg.str());
  }
  PkSolver solver(problem, options);
  if (!problem.pressure_limit_Pa) return solver.SolveForApproach(delta, start);
  solver.SetLimit(std::numeric_limits<double>::infinity());
  NormalSolution elastic = solver.SolveForApproach(delta, start);
  if (elastic.status != SolverStatus::kConverged ||
      !(elastic.pressure_Pa.maxCoeff() > *problem.pressure_limit_Pa)) {
    return elastic;
  }
  solver.SetLimit(*problem.pressure_limit_Pa);
  NormalSolution out = solver.SolveForApproach(delta, &elastic.pressure_Pa);
  std::ostringstream msg;
  msg << "; pressure limit " << *problem.pressure_limit_Pa * 1e-6 << " MPa: " << out.plastic_cells
      << " plastic cells (" << elastic.iterations << " iterations in the elastic solve first)";
  out.message += msg.str();
  return out;
}

}  // namespace railwear
