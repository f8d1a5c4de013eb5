// The studio's Rank window computes `ipd rank`'s ranking on its live session (core/session/session_ranking.h):
// on a study without hand pairs the same order, IPDs, intervals and Holm p-values as the command line's
// computation from the table; a hand edit moves the edited candidate's number.
#include <gtest/gtest.h>

#include "core/demo/variant_study.h"
#include "core/session/session_ranking.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

TEST(SessionRanking, EqualsTheCommandLinesRankingWithoutHandPairs) {
  test::TempDir d;
  VariantStudyOptions v;
  v.variants = 5;  // ambient 0, 0.25, 0.5, 0.75, 1: the true best 0.375 lies between ambient-025 and ambient-050
  v.scenes = 12;
  write_variant_study(d.path(), v);
  // The command line's way: only the (real, variant) pairs registered, intervals, rank_candidates.
  const StudyLabels labels = load_labels(open_study(d.path()));
  TableOptions to;
  to.models = {"det-real"};
  to.only_pairs = ranked_pairs(resolve_rank_domains(labels.study, "real", {}));
  CrossTable table = compute_cross_table(labels, to);
  add_confidence_intervals(&table, BootstrapOptions{});
  RankOptions ro;
  ro.model = "det-real";
  ro.domains = resolve_rank_domains(labels.study, "real", {});
  const Ranking cli = rank_candidates(labels, table, ro);

  const Session s = Session::open(d.path());
  SessionRankRequest request;
  request.model = "det-real";
  request.ref = "real";
  const SessionRanking studio = compute_session_ranking(s, request);
  ASSERT_TRUE(studio.ranking.has_value()) << studio.error;
  ASSERT_EQ(studio.ranking->ranked.size(), 5u);
  EXPECT_EQ(studio.ranking->tests, 4);
  for (size_t k = 0; k < cli.ranked.size(); ++k) {
    const RankedCandidate &a = cli.ranked[k], &b = studio.ranking->ranked[k];
    EXPECT_EQ(a.domain, b.domain) << k;
    EXPECT_EQ(a.rank, b.rank);
    EXPECT_DOUBLE_EQ(a.ipd, b.ipd) << a.domain;
    EXPECT_DOUBLE_EQ(a.ci_low, b.ci_low) << a.domain;
    EXPECT_DOUBLE_EQ(a.ci_high, b.ci_high) << a.domain;
    EXPECT_EQ(a.pairs, b.pairs);
    if (k > 0) {
      EXPECT_DOUBLE_EQ(a.p_holm, b.p_holm) << a.domain;
    }
    EXPECT_EQ(a.in_best_group, b.in_best_group) << a.domain;
  }
  EXPECT_TRUE(studio.ranking->best()->domain == "ambient-025" || studio.ranking->best()->domain == "ambient-050")
      << studio.ranking->best()->domain;
  // Only the reference's cells of the model are in the ranking's table: 5, not the 15 domain pairs.
  EXPECT_EQ(session_rank_table(s, "det-real", "real", BootstrapOptions{}).cells.size(), 5u);
}

TEST(SessionRanking, NoModelIsSaidNotRanked) {
  test::TempDir d;
  VariantStudyOptions v;
  v.variants = 2;
  v.scenes = 3;
  write_variant_study(d.path(), v);
  const Session s = Session::open(d.path());
  const SessionRanking r = compute_session_ranking(s, SessionRankRequest{});
  EXPECT_FALSE(r.ranking.has_value());
  EXPECT_EQ(r.error, "no model: a ranking needs predictions");
}

}  // namespace
}  // namespace ipd
