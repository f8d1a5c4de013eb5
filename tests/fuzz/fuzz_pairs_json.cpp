// Fuzzes the fixed-pairs JSON reader (pairs/<A>__<B>/<stem>.json, read in either name order) as `ipd table`
// and ipd-studio call it, with stored boxes bound to the rocks. Accepted pairs must be in range and one-to-one;
// errors are StudyErrors naming the file.
#include <set>

#include "core/study/study.h"
#include "core/util/atomic_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path root = ipd_fuzz::scratch_dir() / "study";
  ipd::Study study;
  study.root = root.string();
  constexpr int kCountA = 16, kCountB = 12;  // rocks in the real and the synthetic picture
  // Distinct boxes on a grid, so a stored box finds its rock again (or doesn't).
  static const auto rocks = [](int n) {
    std::vector<ipd::Box> out(n);
    for (int k = 0; k < n; ++k) out[k].cx = 0.05 + 0.05 * k, out[k].cy = 0.5, out[k].w = out[k].h = 0.04;
    return out;
  };
  static const std::vector<ipd::Box> gt_a = rocks(kCountA), gt_b = rocks(kCountB);
  // Odd-sized inputs go in the other name order, so the swapped reading is fuzzed too.
  const bool swapped = size % 2 == 1;
  const std::filesystem::path file =
      std::filesystem::path(swapped ? study.pairs_dir("synth", "real") : study.pairs_dir("real", "synth")) /
      "scene.json";
  std::error_code ec;
  std::filesystem::remove_all(root / "pairs", ec);
  ipd_fuzz::write_bytes(file, data, size);
  try {
    const auto fp = ipd::read_fixed_pairs(study, "real", "synth", "scene", gt_a, gt_b);
    if (!fp) ipd_fuzz::fail("the pairs file was not found", file.string());
    std::set<int> used_a, used_b;
    for (const auto& [a, b] : fp->pairs) {
      if (a < 0 || a >= kCountA || b < 0 || b >= kCountB)
        ipd_fuzz::fail("an accepted pair is out of range", file.string());
      if (!used_a.insert(a).second || !used_b.insert(b).second) ipd_fuzz::fail("a rock is paired twice", file.string());
    }
    for (int a : fp->excluded_a)
      if (a < 0 || a >= kCountA) ipd_fuzz::fail("excluded_a out of range", file.string());
    for (int b : fp->excluded_b)
      if (b < 0 || b >= kCountB) ipd_fuzz::fail("excluded_b out of range", file.string());
  } catch (const ipd::StudyError& e) {
    ipd_fuzz::check_message(e.what(), file.string());
  } catch (const ipd::IoError& e) {
    ipd_fuzz::check_message(e.what(), file.string());
  }
  return 0;
}
