// SPDX-License-Identifier: MIT
// The data-parallel loop (core/parallel_for.h): every index once, the serial loop's exception,
// the thread count and who may have threads. No timing here (bench/threads.sh measures).
#include "tessera/core/parallel_for.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/error.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

TEST(ParallelFor, RunsEveryIndexOnceWhateverTheThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    for (int count : {0, 1, 15, 16, 17, 1000}) {
      std::vector<int> runs(static_cast<std::size_t>(count), 0);
      parallel_for(count, threads, [&](int i) { ++runs[static_cast<std::size_t>(i)]; });
      EXPECT_EQ(runs, std::vector<int>(static_cast<std::size_t>(count), 1))
          << count << " indices on " << threads << " threads";
    }
  }
}

TEST(ParallelFor, RethrowsTheExceptionOfTheSmallestIndex) {
  // What a serial loop throws: the first failure in index order, however the indices were
  // shared out.
  for (int threads : {1, 2, 3}) {
    try {
      parallel_for(1000, threads, [](int i) {
        if (i == 977 || i == 450 || i == 451) {
          throw std::runtime_error("index " + std::to_string(i));
        }
      });
      ADD_FAILURE() << "nothing thrown on " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "index 450") << threads << " threads";
    }
  }
}

TEST(ThreadCount, ScopeSetsAndRestores) {
  const int before = thread_count();
  {
    const ThreadCountScope scope(3);
    EXPECT_EQ(thread_count(), 3);
    {
      const ThreadCountScope unchanged(0);  // 0: leaves it
      EXPECT_EQ(thread_count(), 3);
    }
  }
  EXPECT_EQ(thread_count(), before);
  EXPECT_GE(before, 1);
  EXPECT_THROW(set_thread_count(-1), InvalidArgument);
}

// A sphere that says what the test tells it about its thread safety.
class DeclaredSphere final : public ImplicitProblem {
 public:
  explicit DeclaredSphere(bool is_safe) : is_safe_(is_safe) {}
  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    sphere_.evaluate(x, F);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    sphere_.jacobian(x, J);
  }
  bool is_thread_safe() const override { return is_safe_; }

 private:
  Sphere sphere_{1.0};
  bool is_safe_;
};

TEST(ThreadsFor, OnlyThreadSafeDenseProblemsGetThreads) {
  const ThreadCountScope scope(4);
  EXPECT_EQ(threads_for(DeclaredSphere(true)), 4);
  EXPECT_EQ(threads_for(DeclaredSphere(false)), 1);
  // The catalogue's problems are pure functions; the large-n ones are sparse: one thread.
  EXPECT_EQ(threads_for(Torus()), 4);
  EXPECT_EQ(threads_for(ArrheniusBratu(20)), 1);
  // Decorators forward.
  const DeclaredSphere unsafe(false);
  EXPECT_EQ(threads_for(CountedProblem(unsafe)), 1);
  EXPECT_EQ(threads_for(CountedProblem(Sphere(1.0))), 4);
  // A user's problem that says nothing runs on one thread.
  struct Plain final : ImplicitProblem {
    int ambient_dimension() const override { return 3; }
    void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                  Eigen::Ref<Eigen::VectorXd> F) const override {
      F(0) = x(2);
    }
    void jacobian(const Eigen::Ref<const Eigen::VectorXd>&,
                  Eigen::Ref<Eigen::MatrixXd> J) const override {
      J << 0, 0, 1;
    }
  };
  EXPECT_EQ(threads_for(Plain()), 1);
}

TEST(ConcurrentCount, SumsWhatEveryThreadAdded) {
  ConcurrentCount count;
  parallel_for(10000, 3, [&](int i) { count.add(i % 3); });
  EXPECT_EQ(count.total(), 3333 * 3 + 0);  // 3333 ones, 3333 twos, 3334 zeros
}

}  // namespace
}  // namespace tessera
