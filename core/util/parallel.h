// Running independent jobs on every core: fn(0) ... fn(n - 1), each at most once, in no particular order.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace ipd {

// threads <= 0: all hardware threads. The calling thread works too. When a job throws, no new job starts
// and the first exception is rethrown here, on the calling thread, once every worker has stopped (an
// exception escaping a std::thread would call std::terminate).
template <typename Fn>
void parallel_for(size_t n, int threads, Fn&& fn) {
  if (n == 0) return;
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const size_t workers = std::min(n, static_cast<size_t>(threads > 0 ? threads : static_cast<int>(hw)));
  std::atomic<size_t> next{0};
  std::mutex failure_mutex;
  std::exception_ptr failure;
  auto work = [&] {
    for (size_t k; (k = next.fetch_add(1)) < n;) {
      try {
        fn(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next.store(n);  // stop handing out jobs
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace ipd
