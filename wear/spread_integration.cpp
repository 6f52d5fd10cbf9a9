// Adaptive integration over a lateral spread (see spread_integration.h).
#include "wear/spread_integration.h"

#include <algorithm>
#include <cmath>

#include "core/numerics/check.h"

namespace railwear {

namespace {

// Phi(b) - Phi(a) for a <= b, from the nearer tail (no cancellation against 1).
double NormalMass(double a, double b) {
  const double r = 1.0 / std::sqrt(2.0);
  if (a >= 0.0) return 0.5 * (std::erfc(a * r) - std::erfc(b * r));
  if (b <= 0.0) return 0.5 * (std::erfc(-b * r) - std::erfc(-a * r));
  return 1.0 - 0.5 * std::erfc(-a * r) - 0.5 * std::erfc(b * r);
}

double NormalDensity(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * M_PI); }

}  // namespace

std::string_view ToString(SpreadRule v) { return EnumToString(kSpreadRuleNames, v); }

std::vector<double> LinearGaussianWeights(const std::vector<double>& x) {
  const int m = static_cast<int>(x.size());
  RAILWEAR_CHECK(m >= 1);
  std::vector<double> w(m, 0.0);
  const double r = 1.0 / std::sqrt(2.0);
  w.front() += 0.5 * std::erfc(-x.front() * r);  // Phi(x_0): constant below the first node
  w.back() += 0.5 * std::erfc(x.back() * r);     // 1 - Phi(x_m): constant above the last
  for (int i = 0; i + 1 < m; ++i) {
    const double a = x[i], b = x[i + 1], h = b - a;
    RAILWEAR_CHECK(h > 0.0);
    // int_a^b phi = M0, int_a^b x phi = phi(a) - phi(b) = M1; the hats (b - x)/h, (x - a)/h.
    const double m0 = NormalMass(a, b);
    const double m1 = NormalDensity(a) - NormalDensity(b);
    // Both differences are O(h^2) for small h: their rounding is absolute, ~1e-16.
    w[i] += std::max(0.0, (b * m0 - m1) / h);
    w[i + 1] += std::max(0.0, (m1 - a * m0) / h);
  }
  return w;
}

std::vector<double> LinearSpreadNodes(int m) {
  RAILWEAR_CHECK(m >= kMinLinearSpreadNodes && m <= kMaxLinearSpreadNodes && m % 8 == 0);
  std::vector<double> x;
  x.reserve(static_cast<size_t>(m + m / 4));
  for (int j = m / 8; j >= 1; --j) x.push_back(-3.0 - 16.0 * j / m);
  for (int k = -m / 2; k < m / 2; ++k) x.push_back((k + 0.5) * 6.0 / m);
  for (int j = 1; j <= m / 8; ++j) x.push_back(3.0 + 16.0 * j / m);
  return x;
}

std::array<double, 2> SpreadUnit::Integral() const {
  const std::vector<double> w = LinearGaussianWeights(x);
  std::array<double, 2> sum = {0.0, 0.0};
  for (size_t k = 0; k < x.size(); ++k) {
    for (int r = 0; r < 2; ++r) sum[r] += w[k] * value[k][r];
  }
  return sum;
}

std::vector<double> SpreadUnit::FieldIntegral(int r) const {
  if (field.empty()) return {};
  const std::vector<double> w = LinearGaussianWeights(x);
  std::vector<double> sum(field[0][r].size(), 0.0);
  for (size_t k = 0; k < x.size(); ++k) {
    const std::vector<double>& f = field[k][r];
    RAILWEAR_CHECK(f.size() == sum.size());
    for (size_t b = 0; b < f.size(); ++b) sum[b] += w[k] * f[b];
  }
  return sum;
}

double SpreadUnit::Difference(int r, double a, const std::vector<double>* fa, double b,
                              const std::vector<double>* fb) const {
  if (field.empty() || !fa || !fb) return std::abs(a - b);
  RAILWEAR_CHECK(fa->size() == fb->size());
  double l1 = 0.0;
  for (size_t k = 0; k < fa->size(); ++k) l1 += std::abs((*fa)[k] - (*fb)[k]);
  // Never below the area's change (rounding of a field whose bins all moved the same way).
  return std::max(std::abs(a - b), bin_m[r] * l1);
}

void SpreadUnit::SetInitialErrors() {
  error.assign(x.size() - 1, {0.0, 0.0});
  frozen.assign(x.size() - 1, 0);
  RAILWEAR_CHECK(field.empty() || field.size() == x.size());
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    const double mass = NormalMass(x[i], x[i + 1]);
    for (int r = 0; r < 2; ++r) {
      const bool f = !field.empty();
      error[i][r] = mass * Difference(r, value[i + 1][r], f ? &field[i + 1][r] : nullptr,
                                      value[i][r], f ? &field[i][r] : nullptr);
    }
  }
}

void SpreadUnit::Bisect(int interval, const SpreadResponse& midpoint) {
  RAILWEAR_CHECK(interval >= 0 && interval + 1 < static_cast<int>(x.size()));
  const bool fields = !field.empty();
  const std::array<double, 2> before = Integral();
  std::array<std::vector<double>, 2> field_before;
  if (fields) {
    for (int r = 0; r < 2; ++r) {
      RAILWEAR_CHECK(midpoint.field[r].size() == field[0][r].size());
      field_before[r] = FieldIntegral(r);
    }
  }
  x.insert(x.begin() + interval + 1, 0.5 * (x[interval] + x[interval + 1]));
  value.insert(value.begin() + interval + 1, midpoint.value);
  if (fields) field.insert(field.begin() + interval + 1, midpoint.field);
  const std::array<double, 2> after = Integral();
  std::array<double, 2> half;
  for (int r = 0; r < 2; ++r) {
    if (fields) {
      const std::vector<double> field_after = FieldIntegral(r);
      half[r] = 0.5 * Difference(r, after[r], &field_after, before[r], &field_before[r]);
    } else {
      half[r] = 0.5 * std::abs(after[r] - before[r]);
    }
  }
  error[interval] = half;
  error.insert(error.begin() + interval + 1, half);
  frozen.insert(frozen.begin() + interval + 1, 0);
  // The first two levels keep the monotone bound as a floor: a midpoint that happens to lie on
  // the chord (d = 0) must not hide a switch inside a wide interval.
  for (const int i : {interval, interval + 1}) {
    if (x[i + 1] - x[i] > kSpreadBoundWidth * (1.0 + 1e-9)) {
      const double mass = NormalMass(x[i], x[i + 1]);
      for (int r = 0; r < 2; ++r) {
        const double d = Difference(r, value[i + 1][r], fields ? &field[i + 1][r] : nullptr,
                                    value[i][r], fields ? &field[i][r] : nullptr);
        error[i][r] = std::max(error[i][r], mass * d);
      }
    }
  }
}

std::vector<SpreadInterval> SelectSpreadIntervals(const std::vector<SpreadUnit>& units,
                                                  const std::array<double, 2>& rail_total,
                                                  double tolerance, bool* converged) {
  std::array<double, 2> budget, sum = {0.0, 0.0};
  for (int r = 0; r < 2; ++r) budget[r] = tolerance * rail_total[r];
  for (const SpreadUnit& u : units) {
    for (const auto& e : u.error) {
      for (int r = 0; r < 2; ++r) sum[r] += e[r];
    }
  }
  std::array<bool, 2> exceeds;
  for (int r = 0; r < 2; ++r) exceeds[r] = rail_total[r] > 0.0 && sum[r] > budget[r];
  if (converged) *converged = !exceeds[0] && !exceeds[1];
  if (!exceeds[0] && !exceeds[1]) return {};
  // Candidates by their largest estimate relative to an exceeding rail's budget, then unit and
  // interval (stable sort of a list made in that order).
  struct Candidate {
    double score;
    SpreadInterval at;
  };
  std::vector<Candidate> candidates;
  for (int u = 0; u < static_cast<int>(units.size()); ++u) {
    const SpreadUnit& unit = units[u];
    for (int i = 0; i < static_cast<int>(unit.error.size()); ++i) {
      if (unit.x[i + 1] - unit.x[i] <= kMinSpreadInterval * (1.0 + 1e-9)) continue;
      if (unit.frozen[i]) continue;
      double score = 0.0;
      for (int r = 0; r < 2; ++r) {
        if (exceeds[r]) score = std::max(score, unit.error[i][r] / budget[r]);
      }
      if (score > 0.0) candidates.push_back({score, {u, i}});
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  std::vector<int> added(units.size(), 0);
  std::array<double, 2> marked = {0.0, 0.0};
  const auto needs_more = [&](int r) {
    return exceeds[r] && marked[r] < kSpreadMarkingShare * sum[r];
  };
  std::vector<SpreadInterval> chosen;
  for (const Candidate& c : candidates) {
    if (!needs_more(0) && !needs_more(1)) break;
    const SpreadUnit& u = units[c.at.unit];
    if (static_cast<int>(u.x.size()) + added[c.at.unit] >= kMaxSpreadNodes) continue;
    const auto& e = u.error[c.at.interval];
    if (!((needs_more(0) && e[0] > 0.0) || (needs_more(1) && e[1] > 0.0))) continue;
    ++added[c.at.unit];
    for (int r = 0; r < 2; ++r) marked[r] += e[r];
    chosen.push_back(c.at);
  }
  std::sort(chosen.begin(), chosen.end(), [](const SpreadInterval& a, const SpreadInterval& b) {
    return a.unit != b.unit ? a.unit < b.unit : a.interval < b.interval;
  });
  return chosen;
}

std::array<double, 2> SpreadErrorEstimate(const std::vector<SpreadUnit>& units,
                                          const std::array<double, 2>& rail_total) {
  std::array<double, 2> sum = {0.0, 0.0};
  for (const SpreadUnit& u : units) {
    for (const auto& e : u.error) {
      for (int r = 0; r < 2; ++r) sum[r] += e[r];
    }
  }
  for (int r = 0; r < 2; ++r) sum[r] = rail_total[r] > 0.0 ? sum[r] / rail_total[r] : 0.0;
  return sum;
}

SpreadIntegrationSummary RefineSpreads(std::vector<SpreadUnit>* units,
                                       const std::array<double, 2>& fixed_total, double tolerance,
                                       const SpreadEvaluator& evaluate) {
  const auto totals = [&] {
    std::array<double, 2> sum = fixed_total;
    for (const SpreadUnit& u : *units) {
      const std::array<double, 2> q = u.Integral();
      for (int r = 0; r < 2; ++r) sum[r] += q[r];
    }
    return sum;
  };
  // The rail's depth field summed over the units (empty when they have none): the change of a
  // round is measured on it when the units carry fields.
  const bool fields = !units->empty() && !(*units)[0].field.empty();
  const auto field_totals = [&] {
    std::array<std::vector<double>, 2> sum;
    if (!fields) return sum;
    for (const SpreadUnit& u : *units) {
      for (int r = 0; r < 2; ++r) {
        const std::vector<double> f = u.FieldIntegral(r);
        if (sum[r].empty()) sum[r].assign(f.size(), 0.0);
        RAILWEAR_CHECK(f.size() == sum[r].size());
        for (size_t b = 0; b < f.size(); ++b) sum[r][b] += f[b];
      }
    }
    return sum;
  };
  SpreadIntegrationSummary summary;
  summary.adaptive = true;
  summary.tolerance = tolerance;
  int quiet_rounds = 0;  // successive rounds that changed no rail's total above tolerance
  while (true) {
    const std::array<double, 2> before = totals();
    const std::array<std::vector<double>, 2> field_before = field_totals();
    bool converged = false;
    const std::vector<SpreadInterval> chosen =
        SelectSpreadIntervals(*units, before, tolerance, &converged);
    if (chosen.empty()) {  // converged, or nothing left to bisect
      summary.converged = converged;
      break;
    }
    ++summary.rounds;
    std::vector<double> midpoints;
    for (const SpreadInterval& c : chosen) {
      const SpreadUnit& u = (*units)[c.unit];
      midpoints.push_back(0.5 * (u.x[c.interval] + u.x[c.interval + 1]));
    }
    const std::vector<SpreadResponse> values = evaluate(chosen, midpoints);
    RAILWEAR_CHECK(values.size() == chosen.size());
    // Bisect from the last interval of each unit back, so the indices before stay valid.
    for (int k = static_cast<int>(chosen.size()) - 1; k >= 0; --k) {
      SpreadUnit& u = (*units)[chosen[k].unit];
      if (std::isnan(values[k].value[0]) || std::isnan(values[k].value[1])) {
        u.frozen[chosen[k].interval] = 1;
      } else {
        u.Bisect(chosen[k].interval, values[k]);
      }
    }
    const std::array<double, 2> after = totals();
    const std::array<std::vector<double>, 2> field_after = field_totals();
    bool quiet = true;
    for (int r = 0; r < 2; ++r) {
      summary.last_change[r] = after[r] > 0.0 ? std::abs(after[r] - before[r]) / after[r] : 0.0;
      quiet = quiet && summary.last_change[r] <= tolerance;
      if (fields && after[r] > 0.0) {
        double l1 = 0.0;
        for (size_t b = 0; b < field_after[r].size(); ++b)
          l1 += std::abs(field_after[r][b] - field_before[r][b]);
        quiet =
            quiet && (*units)[0].bin_m[r] * l1 <= kSpreadFieldChangeFactor * tolerance * after[r];
      }
    }
    quiet_rounds = quiet ? quiet_rounds + 1 : 0;
    if (quiet_rounds >= 2) {
      summary.converged = true;
      break;
    }
  }
  summary.estimated_error = SpreadErrorEstimate(*units, totals());
  return summary;
}

}  // namespace railwear
