// CowVector (core/util/cow_vector.h): copies share chunks; a write changes only the vector written to.
#include "core/util/cow_vector.h"

#include <gtest/gtest.h>

#include <atomic>
#include <numeric>
#include <string>
#include <thread>

namespace ipd {
namespace {

std::vector<int> iota(int n) {
  std::vector<int> v(n);
  std::iota(v.begin(), v.end(), 0);
  return v;
}

TEST(CowVector, ACopyKeepsItsValuesWhenTheOriginalIsEdited) {
  CowVector<int, 4> v(iota(10));  // chunks [0..3], [4..7], [8, 9]
  const CowVector<int, 4> snapshot = v;
  v.set(5, 50);
  v.edit(9) = 90;
  EXPECT_EQ(v.to_vector(), (std::vector<int>{0, 1, 2, 3, 4, 50, 6, 7, 8, 90}));
  EXPECT_EQ(snapshot.to_vector(), iota(10));
  // Only the chunks written to were copied.
  EXPECT_TRUE(v.shares_element(snapshot, 0));
  EXPECT_FALSE(v.shares_element(snapshot, 4));
  EXPECT_FALSE(v.shares_element(snapshot, 8));
}

TEST(CowVector, PushBackAndTruncateLeaveCopiesAlone) {
  CowVector<std::string, 2> v;
  v.push_back("a");
  v.push_back("b");
  v.push_back("c");  // a second chunk
  const CowVector<std::string, 2> before = v;
  v.truncate(1);
  v.push_back("x");
  v.push_back("y");
  EXPECT_EQ(v.to_vector(), (std::vector<std::string>{"a", "x", "y"}));
  EXPECT_EQ(before.to_vector(), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(v.size(), 3u);
  EXPECT_EQ(v.back(), "y");
  v.truncate(5);  // longer than the vector: nothing changes
  EXPECT_EQ(v.size(), 3u);
  v.truncate(0);
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(before.size(), 3u);
}

TEST(CowVector, IteratesInOrderAndChecksIndices) {
  const CowVector<int, 3> v(iota(7));
  int expected = 0;
  for (const int x : v) EXPECT_EQ(x, expected++);
  EXPECT_EQ(expected, 7);
  EXPECT_EQ(v.end() - v.begin(), 7);
  EXPECT_EQ(v.at(6), 6);
  EXPECT_THROW(v.at(7), std::out_of_range);
  CowVector<int, 3> w = v;
  EXPECT_THROW(w.edit(7), std::out_of_range);
}

// The studio reads a published copy on the UI thread while the worker edits the original: the copy's values
// never change, whatever the writer does meanwhile (run under ThreadSanitizer too, preset "tsan").
TEST(CowVector, ACopyReadOnAnotherThreadWhileTheOriginalIsWritten) {
  CowVector<std::string, 8> v(std::vector<std::string>(100, "old"));
  const CowVector<std::string, 8> snapshot = v;
  std::atomic<bool> done{false};
  std::atomic<int> wrong{0};
  std::thread reader([&] {
    while (!done.load()) {
      for (size_t i = 0; i < snapshot.size(); ++i)
        if (snapshot[i] != "old") wrong.fetch_add(1);
    }
  });
  for (int round = 0; round < 200; ++round) {
    v.set(static_cast<size_t>(round % 100), "new " + std::to_string(round));
    v.push_back("pushed");
    v.truncate(100);
  }
  done = true;
  reader.join();
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_EQ(snapshot.to_vector(), std::vector<std::string>(100, "old"));
  EXPECT_EQ(v[99], "new 199");
}

}  // namespace
}  // namespace ipd
