// Pooled CDFs with member-bootstrap bands (bootstrap_cdf.hpp).
#include "fragmpm/analysis/bootstrap_cdf.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace fragmpm::analysis {

namespace {

/// Percentile of sorted values with linear interpolation between order statistics (type 7).
double percentile(const std::vector<double>& sorted, double p) {
  const double h = p * double(sorted.size() - 1);
  const std::size_t k = static_cast<std::size_t>(std::floor(h));
  if (k + 1 >= sorted.size()) return sorted.back();
  return sorted[k] + (h - double(k)) * (sorted[k + 1] - sorted[k]);
}

}  // namespace

std::vector<double> spaced_points(double lo, double hi, int count, bool log) {
  std::vector<double> x(static_cast<std::size_t>(std::max(count, 2)));
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double t = double(i) / double(n - 1);
    x[i] = log ? lo * std::pow(hi / lo, t) : lo + t * (hi - lo);
  }
  return x;
}

CdfBand bootstrap_cdf_band(std::span<const MemberSample> members, std::span<const double> x,
                           int replicates, std::uint64_t seed, double level) {
  const std::size_t M = members.size(), G = x.size();
  // Per member: count and mass at or below each x, and the totals, so that a replicate is a sum of
  // M rows (O(M G)) instead of a pass over all fragments.
  std::vector<std::vector<double>> count(M, std::vector<double>(G)),
      mass(M, std::vector<double>(G));
  std::vector<double> n_total(M), m_total(M);
  bool any = false;
  for (std::size_t m = 0; m < M; ++m) {
    const MemberSample& s = members[m];
    if (s.value.size() != s.mass.size())
      throw std::invalid_argument("bootstrap_cdf_band: value and mass sizes differ");
    std::vector<std::size_t> order(s.value.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return s.value[a] < s.value[b]; });
    std::size_t k = 0;
    double c = 0, w = 0;
    for (std::size_t g = 0; g < G; ++g) {
      while (k < order.size() && s.value[order[k]] <= x[g]) {
        c += 1;
        w += s.mass[order[k]];
        ++k;
      }
      count[m][g] = c;
      mass[m][g] = w;
    }
    n_total[m] = double(s.value.size());
    for (double v : s.mass) m_total[m] += v;
    any = any || !s.value.empty();
  }
  if (!any) throw std::invalid_argument("bootstrap_cdf_band: no member has fragments");

  auto pooled = [&](const std::vector<std::size_t>& pick, std::vector<double>& fn,
                    std::vector<double>& fm) {
    double nt = 0, mt = 0;
    std::fill(fn.begin(), fn.end(), 0.0);
    std::fill(fm.begin(), fm.end(), 0.0);
    for (std::size_t m : pick) {
      nt += n_total[m];
      mt += m_total[m];
      for (std::size_t g = 0; g < G; ++g) {
        fn[g] += count[m][g];
        fm[g] += mass[m][g];
      }
    }
    for (std::size_t g = 0; g < G; ++g) {
      fn[g] = nt > 0 ? fn[g] / nt : 0.0;
      fm[g] = mt > 0 ? fm[g] / mt : 0.0;
    }
    return nt > 0 && mt > 0;
  };

  CdfBand band;
  band.x.assign(x.begin(), x.end());
  band.replicates = replicates;
  band.seed = seed;
  band.number.resize(G);
  band.mass.resize(G);
  std::vector<std::size_t> all(M);
  for (std::size_t m = 0; m < M; ++m) all[m] = m;
  pooled(all, band.number, band.mass);

  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> draw(0, M - 1);
  std::vector<std::vector<double>> rn(G), rm(G);
  std::vector<std::size_t> pick(M);
  std::vector<double> fn(G), fm(G);
  for (int r = 0; r < replicates; ++r) {
    for (std::size_t& p : pick) p = draw(rng);
    if (!pooled(pick, fn, fm)) continue;  // only empty members drawn: no CDF to add
    for (std::size_t g = 0; g < G; ++g) {
      rn[g].push_back(fn[g]);
      rm[g].push_back(fm[g]);
    }
  }
  const double lo = 0.5 - level / 2, hi = 0.5 + level / 2;
  for (auto* v : {&band.number_low, &band.number_high, &band.mass_low, &band.mass_high})
    v->resize(G);
  for (std::size_t g = 0; g < G; ++g) {
    if (rn[g].empty()) {
      band.number_low[g] = band.number_high[g] = band.number[g];
      band.mass_low[g] = band.mass_high[g] = band.mass[g];
      continue;
    }
    std::sort(rn[g].begin(), rn[g].end());
    std::sort(rm[g].begin(), rm[g].end());
    band.number_low[g] = percentile(rn[g], lo);
    band.number_high[g] = percentile(rn[g], hi);
    band.mass_low[g] = percentile(rm[g], lo);
    band.mass_high[g] = percentile(rm[g], hi);
  }
  return band;
}

}  // namespace fragmpm::analysis
