// Maximum-likelihood size-distribution fits (size_fits.hpp; derivations in docs/design.md).
#include "fragmpm/analysis/size_fits.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace fragmpm::analysis {

namespace {

void check_samples(std::span<const double> d, std::size_t at_least, const char* what) {
  if (d.size() < at_least)
    throw std::invalid_argument(std::string(what) + ": expected at least " +
                                std::to_string(at_least) + " samples, got " +
                                std::to_string(d.size()));
  for (double x : d)
    if (!(x > 0.0) || !std::isfinite(x))
      throw std::invalid_argument(std::string(what) + ": sizes must be positive and finite");
}

/// KS distance between the sorted samples' empirical CDF and a model CDF.
template <class Cdf>
double ks_distance(const std::vector<double>& sorted, Cdf cdf) {
  const double n = static_cast<double>(sorted.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const double f = cdf(sorted[i]);
    worst = std::max({worst, std::abs(f - double(i) / n), std::abs(double(i + 1) / n - f)});
  }
  return worst;
}

}  // namespace

double normal_quantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("normal_quantile: p outside (0, 1)");
  // P. J. Acklam's coefficients.
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double dd[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                              3.754408661907416e+00};
  double x;
  if (p < 0.02425) {
    const double q = std::sqrt(-2 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((dd[0] * q + dd[1]) * q + dd[2]) * q + dd[3]) * q + 1);
  } else if (p > 1 - 0.02425) {
    const double q = std::sqrt(-2 * std::log(1 - p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((dd[0] * q + dd[1]) * q + dd[2]) * q + dd[3]) * q + 1);
  } else {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  }
  // One Halley step on Φ(x) − p.
  const double e = 0.5 * std::erfc(-x / std::sqrt(2.0)) - p;
  const double u = e * std::sqrt(2 * M_PI) * std::exp(x * x / 2);
  return x - u / (1 + x * u / 2);
}

double chi_squared_quantile(double p, double k) {
  // Wilson & Hilferty: (χ²/k)^(1/3) is nearly normal with mean 1 − 2/(9k), variance 2/(9k).
  const double v = 2.0 / (9.0 * k);
  const double z = normal_quantile(p);
  return k * std::pow(1.0 - v + z * std::sqrt(v), 3);
}

RosinRammlerFit fit_rosin_rammler(std::span<const double> d_in, double level) {
  check_samples(d_in, 3, "Rosin-Rammler fit");
  std::vector<double> d(d_in.begin(), d_in.end());
  std::sort(d.begin(), d.end());
  if (d.front() == d.back())
    throw std::invalid_argument("Rosin-Rammler fit: all samples are equal");
  const double N = static_cast<double>(d.size());
  // Work with x = d / g (g the geometric mean) so that xⁿ stays near 1 for every n.
  double mean_log = 0.0;
  for (double x : d) mean_log += std::log(x);
  mean_log /= N;
  const double g = std::exp(mean_log);
  std::vector<double> lx(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) lx[i] = std::log(d[i] / g);  // mean(lx) = 0
  // Score of the profile likelihood in n: s(n) = 1/n − Σ xⁿ ln x / Σ xⁿ (decreasing in n), and
  // s'(n) = −1/n² − [Σ xⁿ ln²x Σ xⁿ − (Σ xⁿ ln x)²] / (Σ xⁿ)².
  auto score = [&](double n, double* slope) {
    double s0 = 0, s1 = 0, s2 = 0;
    for (double l : lx) {
      const double z = std::exp(n * l);
      s0 += z;
      s1 += z * l;
      s2 += z * l * l;
    }
    if (slope) *slope = -1.0 / (n * n) - (s2 * s0 - s1 * s1) / (s0 * s0);
    return 1.0 / n - s1 / s0;
  };
  double lo = 1e-3, hi = 1e3;
  double n = 1.0;
  for (int it = 0; it < 200; ++it) {
    double slope = 0;
    const double s = score(n, &slope);
    if (s > 0)
      lo = n;
    else
      hi = n;
    double next = n - s / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - n) < 1e-13 * n) {
      n = next;
      break;
    }
    n = next;
  }
  double mean_zn = 0.0;
  for (double l : lx) mean_zn += std::exp(n * l);
  mean_zn /= N;
  const double d0 = g * std::pow(mean_zn, 1.0 / n);

  // Observed information at the MLE (u = ln(d/d₀), z = (d/d₀)ⁿ, Σ z = N):
  //   −∂²ℓ/∂n² = N/n² + Σ z u²,  −∂²ℓ/∂d₀² = n² N / d₀²,  −∂²ℓ/∂n∂d₀ = −(n/d₀) Σ z u.
  double szu = 0, szu2 = 0;
  for (double x : d) {
    const double u = std::log(x / d0);
    const double z = std::exp(n * u);
    szu += z * u;
    szu2 += z * u * u;
  }
  const double Jnn = N / (n * n) + szu2;
  const double Jdd = n * n * N / (d0 * d0);
  const double Jnd = -(n / d0) * szu;
  const double det = Jnn * Jdd - Jnd * Jnd;
  const double var_n = Jdd / det, var_d0 = Jnn / det;
  const double z = normal_quantile(0.5 + level / 2);
  RosinRammlerFit fit;
  fit.n = n;
  fit.d0 = d0;
  fit.n_ci = {n - z * std::sqrt(var_n), n + z * std::sqrt(var_n)};
  fit.d0_ci = {d0 - z * std::sqrt(var_d0), d0 + z * std::sqrt(var_d0)};
  fit.d_low = d.front();
  fit.d_high = d.back();
  fit.samples = d.size();
  fit.ks = ks_distance(d, [&](double x) { return 1.0 - std::exp(-std::pow(x / d0, n)); });
  return fit;
}

PowerLawFit fit_power_law(std::span<const double> d_in, double d_min, double d_max, double level) {
  if (!(d_min > 0.0)) throw std::invalid_argument("power-law fit: d_min must be positive");
  if (!(d_max > d_min)) throw std::invalid_argument("power-law fit: d_max must exceed d_min");
  std::vector<double> tail;
  for (double x : d_in)
    if (x >= d_min && x <= d_max) tail.push_back(x);
  check_samples(tail, 2, "power-law fit");
  std::sort(tail.begin(), tail.end());
  const double n = static_cast<double>(tail.size());
  double S = 0.0;  // Σ ln(d/d_min)
  for (double x : tail) S += std::log(x / d_min);
  if (!(S > 0.0)) throw std::invalid_argument("power-law fit: every sample equals d_min");
  PowerLawFit fit;
  fit.d_min = d_min;
  fit.d_max = d_max;
  fit.tail = tail.size();
  fit.samples = d_in.size();
  fit.d_high = tail.back();
  if (!std::isfinite(d_max)) {
    fit.exponent = n / S;
    // 2 D S ~ χ²(2n): the interval [χ²_{(1−L)/2}, χ²_{(1+L)/2}] / (2 S).
    fit.exponent_ci = {chi_squared_quantile(0.5 - level / 2, 2 * n) / (2 * S),
                       chi_squared_quantile(0.5 + level / 2, 2 * n) / (2 * S)};
    fit.ks = ks_distance(tail, [&](double x) { return 1.0 - std::pow(x / d_min, -fit.exponent); });
    return fit;
  }
  // Truncated law: f(d) = D d^(−D−1) / (d_min^(−D) − d_max^(−D)). With r = d_max/d_min and
  // t = ln r, ℓ(D)/n = ln D − D S/n − ln(1 − r^(−D)) + const, so the score is
  //   1/D − S/n − t r^(−D) / (1 − r^(−D))  (decreasing in D),
  // and the observed information n [1/D² − t² r^(−D) / (1 − r^(−D))²].
  const double t = std::log(d_max / d_min);
  auto score = [&](double D) {
    const double q = std::exp(-D * t);
    return 1.0 / D - S / n - t * q / (1.0 - q);
  };
  double lo = 1e-6, hi = 50.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (score(mid) > 0 ? lo : hi) = mid;
  }
  const double D = 0.5 * (lo + hi);
  const double q = std::exp(-D * t);
  const double info = n * (1.0 / (D * D) - t * t * q / ((1.0 - q) * (1.0 - q)));
  const double z = normal_quantile(0.5 + level / 2);
  fit.exponent = D;
  fit.exponent_ci = {D - z / std::sqrt(info), D + z / std::sqrt(info)};
  fit.ks = ks_distance(tail, [&](double x) { return (1.0 - std::pow(x / d_min, -D)) / (1.0 - q); });
  return fit;
}

PowerLawFit fit_power_law_csn(std::span<const double> d_in, std::size_t min_tail, double level) {
  check_samples(d_in, std::max<std::size_t>(min_tail, 2), "power-law fit");
  std::vector<double> d(d_in.begin(), d_in.end());
  std::sort(d.begin(), d.end());
  const std::size_t N = d.size();
  // Suffix sums of ln d give S(d_min) = Σ_{i ≥ k} ln dᵢ − (N − k) ln d_k in O(1) per candidate.
  std::vector<double> suffix(N + 1, 0.0);
  for (std::size_t i = N; i-- > 0;) suffix[i] = suffix[i + 1] + std::log(d[i]);
  double best_ks = std::numeric_limits<double>::infinity();
  std::size_t best = 0;
  for (std::size_t k = 0; k + min_tail <= N; ++k) {
    if (k > 0 && d[k] == d[k - 1]) continue;  // distinct candidates only
    const double m = double(N - k);
    const double S = suffix[k] - m * std::log(d[k]);
    if (!(S > 0.0)) continue;
    const double D = m / S;
    double ks = 0.0;
    for (std::size_t i = k; i < N; ++i) {
      const double f = 1.0 - std::pow(d[i] / d[k], -D);
      const double j = double(i - k);
      ks = std::max({ks, std::abs(f - j / m), std::abs((j + 1) / m - f)});
    }
    if (ks < best_ks) {
      best_ks = ks;
      best = k;
    }
  }
  if (!std::isfinite(best_ks))
    throw std::invalid_argument("power-law fit: no candidate d_min has a non-degenerate tail");
  return fit_power_law(d, d[best], std::numeric_limits<double>::infinity(), level);
}

}  // namespace fragmpm::analysis
