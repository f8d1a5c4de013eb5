#include "tests/support/stats_study.h"

#include <fmt/format.h>

#include <cstdint>

#include "tests/support/test_support.h"

namespace ipd::test {

namespace {

struct Lcg {
  std::uint64_t s;
  double next() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) / 9007199254740992.0;
  }
};

}  // namespace

void write_stats_study(const std::string& root, StatsStudyVariant variant) {
  write_text(root + "/study.yaml",
             "domains: [real, principled, hapke]\nimage_size: [1000, 800]\nmodels: {det: {trained_on: real}}\n");
  const char* domains[] = {"real", "principled", "hapke"};
  for (int scene = 0; scene < 12; ++scene) {
    for (int d = 0; d < 3; ++d) {
      int source = d;  // whose files this domain gets
      if (variant == StatsStudyVariant::kHapkeIsPrincipled && d == 2) source = 1;
      if (variant == StatsStudyVariant::kPrincipledIsReal && d == 1) source = 0;
      Lcg rocks{static_cast<std::uint64_t>(1000 + scene)};
      Lcg jitter{static_cast<std::uint64_t>(77 * source + scene)};
      std::string gt, pred;
      for (int k = 0; k < 10; ++k) {
        const double cx = 0.1 + 0.8 * rocks.next(), cy = 0.1 + 0.8 * rocks.next();
        const double w = 0.02 + 0.1 * rocks.next(), h = w * (0.7 + 0.4 * rocks.next());
        const double conf = 0.3 + 0.65 * rocks.next();
        // the same rock, labelled again in another domain: centre off by up to 0.2% of the picture
        const double jx = source == 0 ? 0 : 0.004 * (jitter.next() - 0.5),
                     jy = source == 0 ? 0 : 0.004 * (jitter.next() - 0.5);
        gt += fmt::format("0 {:.6f} {:.6f} {:.6f} {:.6f}\n", cx + jx, cy + jy, w, h);
        if (source == 0 && k % 7 == 3) continue;  // real misses some rocks entirely
        double shift = source == 0 ? 0.1 : source == 1 ? 0.15 + 0.1 * jitter.next() : (w < 0.06 ? 0.6 : 0.2);
        pred += fmt::format("0 {:.6f} {:.6f} {:.6f} {:.6f} {:.3f}\n", cx + jx + shift * w, cy + jy, w, h, conf);
      }
      const std::string stem = fmt::format("s{:02d}", scene);
      write_text(root + "/" + domains[d] + "/labels/" + stem + ".txt", gt);
      write_text(root + "/" + domains[d] + "/predictions/det/" + stem + ".txt", pred);
    }
  }
}

}  // namespace ipd::test
