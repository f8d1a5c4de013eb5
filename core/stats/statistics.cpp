#include "core/stats/statistics.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace ipd {

namespace {

std::uint64_t splitmix64(std::uint64_t* state) {
  std::uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::uint64_t fnv1a(std::string_view s) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

// Percentile interval and standard deviation of resampled estimates (NaNs already removed).
void summarise(std::vector<double> values, double level, Interval* out) {
  out->resamples = static_cast<int>(values.size());
  if (values.size() < 2) return;
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / values.size();
  double ss = 0;
  for (double v : values) ss += (v - mean) * (v - mean);
  out->se = std::sqrt(ss / (values.size() - 1));
  std::sort(values.begin(), values.end());
  auto at = [&](double q) {
    const double h = q * (values.size() - 1);
    const size_t lo = static_cast<size_t>(std::floor(h));
    const size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (h - lo) * (values[hi] - values[lo]);
  };
  out->low = at(0.5 * (1 - level));
  out->high = at(1 - 0.5 * (1 - level));
}

}  // namespace

double pooled_mean(const std::vector<SceneSum>& scenes) {
  double sum = 0;
  long count = 0;
  for (const auto& s : scenes) {
    sum += s.sum;
    count += s.count;
  }
  return count > 0 ? sum / static_cast<double>(count) : kNaN;
}

SeededIndexSource::SeededIndexSource(std::uint64_t seed, std::string_view key) {
  std::uint64_t s = seed ^ fnv1a(key);
  state_ = splitmix64(&s);
}

std::uint64_t SeededIndexSource::next() { return splitmix64(&state_); }

void SeededIndexSource::draw(std::uint32_t bound, std::vector<std::uint32_t>* out) {
  // Lemire's multiply-shift on the top 32 bits: bias below 2^-32 * bound, far under bootstrap noise.
  for (auto& v : *out) v = static_cast<std::uint32_t>(((next() >> 32) * bound) >> 32);
}

void FixedIndexSource::draw(std::uint32_t bound, std::vector<std::uint32_t>* out) {
  if (next_ >= draws_.size()) throw std::logic_error("FixedIndexSource: no draws left");
  const auto& d = draws_[next_++];
  if (d.size() != out->size())
    throw std::logic_error(
        fmt::format("FixedIndexSource: draw {} has {} values, {} wanted", next_, d.size(), out->size()));
  for (auto v : d)
    if (v >= bound) throw std::logic_error(fmt::format("FixedIndexSource: value {} >= bound {}", v, bound));
  *out = d;
}

std::string BootstrapOptions::validate() const {
  // One resample has no spread: it would give no interval at all, without a word.
  if (resamples < 0 || resamples == 1)
    return fmt::format(
        "the number of bootstrap resamples must be 0 (no intervals) or at least 2 (an interval needs two "
        "resamples), not {}",
        resamples);
  if (!(level > 0 && level < 1))
    return fmt::format("the interval level must be between 0 and 1 (e.g. 0.95), not {}", level);
  return {};
}

std::string CompareOptions::validate() const {
  if (permutations < 0) return fmt::format("the number of permutations must be >= 0, not {}", permutations);
  return bootstrap.validate();
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double h = std::clamp(q, 0.0, 1.0) * (values.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(h));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - lo) * (values[hi] - values[lo]);
}

std::vector<double> quantile_edges(const std::vector<double>& values, int bins) {
  std::vector<double> edges;
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  for (int k = 1; k < bins; ++k) edges.push_back(quantile(sorted, static_cast<double>(k) / bins));
  return edges;
}

namespace {

// Scenes as two flat arrays (cache-friendly for 10^4+ scenes).
struct FlatScenes {
  std::vector<double> sum;
  std::vector<double> count;  // as double: exact for any realistic count, and one kind of add
  explicit FlatScenes(const std::vector<SceneSum>& scenes) {
    sum.reserve(scenes.size());
    count.reserve(scenes.size());
    for (const auto& s : scenes) {
      sum.push_back(s.sum);
      count.push_back(static_cast<double>(s.count));
    }
  }
};

// One resample's pooled mean; next() gives the scene indices in order. Four accumulators break the chain
// of dependent additions (the loop is latency-bound otherwise).
template <typename NextIndex>
double resampled_mean(const FlatScenes& f, std::uint32_t n, NextIndex&& next) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0, c0 = 0, c1 = 0, c2 = 0, c3 = 0;
  std::uint32_t k = 0;
  for (; k + 4 <= n; k += 4) {
    const std::uint32_t i0 = next(), i1 = next(), i2 = next(), i3 = next();
    s0 += f.sum[i0], c0 += f.count[i0];
    s1 += f.sum[i1], c1 += f.count[i1];
    s2 += f.sum[i2], c2 += f.count[i2];
    s3 += f.sum[i3], c3 += f.count[i3];
  }
  for (; k < n; ++k) {
    const std::uint32_t i = next();
    s0 += f.sum[i], c0 += f.count[i];
  }
  const double count = (c0 + c1) + (c2 + c3);
  return count > 0 ? ((s0 + s1) + (s2 + s3)) / count : kNaN;
}

template <typename Resample>
Interval bootstrap_with(const std::vector<SceneSum>& scenes, const BootstrapOptions& options, Resample&& resample) {
  if (const auto e = options.validate(); !e.empty()) throw std::invalid_argument(e);
  Interval out;
  out.estimate = pooled_mean(scenes);
  // One scene with pairs resamples to itself: a zero-width "interval" would claim a certainty it lacks.
  const auto with_pairs = std::count_if(scenes.begin(), scenes.end(), [](const SceneSum& s) { return s.count > 0; });
  if (std::isnan(out.estimate) || options.resamples == 0 || with_pairs < 2) return out;
  const FlatScenes flat(scenes);
  std::vector<double> values;
  values.reserve(options.resamples);
  for (int r = 0; r < options.resamples; ++r) {
    const double v = resample(flat, static_cast<std::uint32_t>(scenes.size()));
    if (!std::isnan(v)) values.push_back(v);
  }
  summarise(std::move(values), options.level, &out);
  return out;
}

}  // namespace

Interval bootstrap_pooled_mean(const std::vector<SceneSum>& scenes, const BootstrapOptions& options,
                               IndexSource& draws) {
  std::vector<std::uint32_t> idx;
  return bootstrap_with(scenes, options, [&](const FlatScenes& f, std::uint32_t n) {
    idx.resize(n);
    draws.draw(n, &idx);
    size_t k = 0;
    return resampled_mean(f, n, [&] { return idx[k++]; });
  });
}

Interval bootstrap_pooled_mean(const std::vector<SceneSum>& scenes, const BootstrapOptions& options,
                               std::string_view key) {
  // The same draws as SeededIndexSource(options.seed, key), generated inline (no buffer, no virtual call).
  SeededIndexSource draws(options.seed, key);
  return bootstrap_with(scenes, options, [&](const FlatScenes& f, std::uint32_t n) {
    return resampled_mean(f, n, [&] { return static_cast<std::uint32_t>(((draws.next() >> 32) * n) >> 32); });
  });
}

namespace {
struct Totals {
  double sa = 0, sb = 0;
  long na = 0, nb = 0;
  double delta() const { return (na > 0 && nb > 0) ? sa / na - sb / nb : kNaN; }
};
}  // namespace

Comparison compare_paired(const std::vector<PairedScene>& scenes, const CompareOptions& options,
                          IndexSource& resample_draws, IndexSource& permutation_draws) {
  if (const auto e = options.validate(); !e.empty()) throw std::invalid_argument(e);
  Comparison c;
  c.scenes = static_cast<int>(scenes.size());
  Totals all;
  double common_a = 0, common_b = 0;
  for (const auto& s : scenes) {
    all.sa += s.a.sum;
    all.na += s.a.count;
    all.sb += s.b.sum;
    all.nb += s.b.count;
    common_a += s.common_a.sum;
    common_b += s.common_b.sum;
    c.pairs_common += s.common_a.count;
  }
  c.pairs_a = all.na;
  c.pairs_b = all.nb;
  c.ipd_a = all.na > 0 ? all.sa / all.na : kNaN;
  c.ipd_b = all.nb > 0 ? all.sb / all.nb : kNaN;
  c.delta.estimate = all.delta();
  if (c.pairs_common > 0) c.delta_common = (common_a - common_b) / static_cast<double>(c.pairs_common);
  // Fewer than two scenes: no interval (a resample is the scene itself) and no test (its only other swap
  // pattern mirrors it, p = 1 whatever the data).
  if (std::isnan(c.delta.estimate) || scenes.size() < 2) return c;

  const auto n = static_cast<std::uint32_t>(scenes.size());
  std::vector<std::uint32_t> idx(n);
  if (options.bootstrap.resamples > 0) {
    std::vector<double> values;
    values.reserve(options.bootstrap.resamples);
    for (int r = 0; r < options.bootstrap.resamples; ++r) {
      resample_draws.draw(n, &idx);
      Totals t;
      for (auto i : idx) {
        t.sa += scenes[i].a.sum;
        t.na += scenes[i].a.count;
        t.sb += scenes[i].b.sum;
        t.nb += scenes[i].b.count;
      }
      const double d = t.delta();
      if (!std::isnan(d)) values.push_back(d);
    }
    summarise(std::move(values), options.bootstrap.level, &c.delta);
  }
  if (options.permutations > 0) {
    // |Δ*| >= |Δ| up to rounding: when a and b are the same, every Δ* is 0 (or ±1e-17) and p must be 1.
    const double observed = std::abs(c.delta.estimate) - 1e-12 * std::max(1.0, std::abs(c.delta.estimate));
    long extreme = 0;
    for (int r = 0; r < options.permutations; ++r) {
      permutation_draws.draw(2, &idx);
      Totals t;
      for (std::uint32_t k = 0; k < n; ++k) {
        const auto& s = scenes[k];
        const bool swap = idx[k] != 0;
        t.sa += swap ? s.b.sum : s.a.sum;
        t.na += swap ? s.b.count : s.a.count;
        t.sb += swap ? s.a.sum : s.b.sum;
        t.nb += swap ? s.a.count : s.b.count;
      }
      const double d = t.delta();
      if (!std::isnan(d) && std::abs(d) >= observed) ++extreme;
    }
    c.permutations = options.permutations;
    c.p_value = (1.0 + extreme) / (options.permutations + 1.0);
  }
  return c;
}

namespace {
// Every sign pattern once, in binary order: draw k sets scene i's swap bit to bit i of k.
class EverySignPattern : public IndexSource {
 public:
  void draw(std::uint32_t, std::vector<std::uint32_t>* out) override {
    for (size_t i = 0; i < out->size(); ++i) (*out)[i] = static_cast<std::uint32_t>((next_ >> i) & 1u);
    ++next_;
  }

 private:
  std::uint64_t next_ = 0;
};
}  // namespace

Comparison compare_paired(const std::vector<PairedScene>& scenes, const CompareOptions& options, std::string_view key) {
  SeededIndexSource resample(options.bootstrap.seed, std::string(key) + "/bootstrap");
  const size_t n = scenes.size();
  if (options.permutations > 0 && n < 31 &&
      (std::uint64_t{1} << n) <= static_cast<std::uint64_t>(options.permutations)) {
    // Few scenes: enumerate all 2^n swaps instead of sampling them, so p is exact and no seed changes it.
    CompareOptions all = options;
    all.permutations = static_cast<int>(std::uint64_t{1} << n);
    EverySignPattern patterns;
    Comparison c = compare_paired(scenes, all, resample, patterns);
    if (!std::isnan(c.p_value)) {
      // The observed pattern is among those enumerated: p = #{|Δ*| >= |Δ|} / 2^n, not (1 + #) / (N + 1).
      const long extreme = std::lround(c.p_value * (all.permutations + 1.0)) - 1;
      c.p_value = static_cast<double>(extreme) / all.permutations;
      c.exact_p = true;
    }
    return c;
  }
  SeededIndexSource permute(options.bootstrap.seed, std::string(key) + "/permutation");
  return compare_paired(scenes, options, resample, permute);
}

namespace {
std::vector<double> average_ranks(const std::vector<double>& v) {
  std::vector<size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t i, size_t j) { return v[i] < v[j]; });
  std::vector<double> rank(v.size());
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double r = 0.5 * (i + j) + 1;  // 1-based average rank of the tie group
    for (size_t k = i; k <= j; ++k) rank[order[k]] = r;
    i = j + 1;
  }
  return rank;
}
}  // namespace

double spearman(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 2) return kNaN;
  const auto rx = average_ranks(x), ry = average_ranks(y);
  const double mx = std::accumulate(rx.begin(), rx.end(), 0.0) / rx.size();
  const double my = std::accumulate(ry.begin(), ry.end(), 0.0) / ry.size();
  double sxy = 0, sxx = 0, syy = 0;
  for (size_t i = 0; i < rx.size(); ++i) {
    sxy += (rx[i] - mx) * (ry[i] - my);
    sxx += (rx[i] - mx) * (rx[i] - mx);
    syy += (ry[i] - my) * (ry[i] - my);
  }
  if (sxx == 0 || syy == 0) return kNaN;
  return sxy / std::sqrt(sxx * syy);
}

}  // namespace ipd
