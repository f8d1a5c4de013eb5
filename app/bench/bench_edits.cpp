// `ipd bench edits STUDY`: the latency of manual edits in a study, as ipd-studio makes them.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <random>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/session/session.h"

namespace ipd::cli {

// `ipd bench edits STUDY`: how long one manual edit takes, live IPD update included (the GUI's budget is
// 1 ms), over random pair / unpair / exclude / undo operations.
Runner add_bench_edits(CLI::App* bench) {
  struct Args {
    std::string study;
    int edits = 2000;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = bench->add_subcommand("edits", "Latency of manual edits with the live IPD update (ipd-studio)");
  cmd->add_option("STUDY", args->study, "Study directory")->required();
  cmd->add_option("--edits", args->edits, "Number of edits")->check(CLI::Range(1, 1000000));
  return [args]() -> int {
    const auto t0 = std::chrono::steady_clock::now();
    Session s = Session::open(args->study);
    const double open_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (s.scenes().empty()) throw StudyError(args->study + ": no scene to edit");
    std::mt19937 gen(1);
    struct {
      std::mt19937& g;
      int below(int n) { return static_cast<int>(g() % static_cast<unsigned>(n)); }
    } rng{gen};
    std::vector<double> us;
    size_t rocks = 0;
    for (int k = 0; k < args->edits; ++k) {
      const int scene = rng.below(static_cast<int>(s.scenes().size()));
      const int nl = static_cast<int>(s.gt(Side::kA, scene).size()),
                nr = static_cast<int>(s.gt(Side::kB, scene).size());
      if (nl == 0 || nr == 0) continue;
      rocks += nl + nr;
      const int op = rng.below(4);
      const auto e0 = std::chrono::steady_clock::now();
      if (op == 0)
        s.apply(scene, Edit::pair(rng.below(nl), rng.below(nr)));
      else if (op == 1)
        s.apply(scene, Edit::unpair(Side::kA, rng.below(nl)));
      else if (op == 2)
        s.apply(scene, Edit::toggle_exclude(Side::kB, rng.below(nr)));
      else
        s.undo();
      volatile double ipd = s.cell().ipd;  // what the panel shows next frame
      (void)ipd;
      us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - e0).count());
    }
    std::sort(us.begin(), us.end());
    fmt::print(
        "{}: opened in {:.1f} ms ({} scenes in view, {} models); {} edits on scenes of {:.1f} rocks on average\n",
        args->study, open_ms, s.scenes().size(), s.study().models.size(), us.size(),
        us.empty() ? 0.0 : static_cast<double>(rocks) / us.size());
    if (!us.empty())
      fmt::print("edit_us median={:.1f} p95={:.1f} max={:.1f}\n", us[us.size() / 2], us[us.size() * 95 / 100],
                 us.back());
    return kOk;
  };
}

}  // namespace ipd::cli
