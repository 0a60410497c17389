// SPDX-License-Identifier: MIT
// A problem that is not thread-safe (ImplicitProblem::is_thread_safe) is called from one thread
// only, through a whole covering and its report, however many threads are allowed; one that is
// gets the same mesh on threads.
#include <gtest/gtest.h>

#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "tessera/core/parallel_for.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/examples.h"
#include "tessera/report/mesh_report.h"

namespace tessera {
namespace {

// The unit sphere, recording the threads that evaluate F and DF.
class RecordingSphere final : public ImplicitProblem {
 public:
  explicit RecordingSphere(bool is_safe) : is_safe_(is_safe) {}
  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    record();
    sphere_.evaluate(x, F);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    record();
    sphere_.jacobian(x, J);
  }
  std::string name() const override { return "sphere"; }
  bool is_thread_safe() const override { return is_safe_; }

  std::set<std::thread::id> threads() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return threads_;
  }

 private:
  void record() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    threads_.insert(std::this_thread::get_id());
  }
  Sphere sphere_{1.0};
  bool is_safe_;
  mutable std::mutex mutex_;
  mutable std::set<std::thread::id> threads_;
};

struct RecordedRun {
  CoveringResult result;
  MeshReport report;
  std::set<std::thread::id> threads;
};

// The sphere at tolerance 0.01 by `method`, with its report (validation and every distance).
RecordedRun cover_recording(const std::string& method, bool is_safe) {
  ProblemSetup setup = make_catalogue_problem("sphere");
  auto problem = std::make_unique<RecordingSphere>(is_safe);
  const RecordingSphere& recording = *problem;
  setup.problem = std::move(problem);
  MethodSettings settings;
  settings.tolerance = 0.01;
  RecordedRun run;
  run.result = cover(setup, find_covering_method(method), settings);
  run.report = make_report(run.result.mesh, setup, "sphere", nullptr, {});
  run.threads = recording.threads();
  return run;
}

TEST(ThreadSafety, ProblemNotThreadSafeIsEvaluatedOnOneThread) {
  const ThreadCountScope scope(3);
  for (const char* method : {"atlas", "front"}) {
    const RecordedRun run = cover_recording(method, /*is_safe=*/false);
    ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
    EXPECT_EQ(run.result.summary.threads, 1);
    EXPECT_EQ(run.threads, std::set<std::thread::id>{std::this_thread::get_id()}) << method;
  }
}

TEST(ThreadSafety, ThreadSafeProblemGetsTheSameMeshOnThreads) {
  const ThreadCountScope scope(3);
  for (const char* method : {"atlas", "front"}) {
    const RecordedRun serial = cover_recording(method, /*is_safe=*/false);
    const RecordedRun threaded = cover_recording(method, /*is_safe=*/true);
    EXPECT_EQ(threaded.result.summary.threads, 3);
    EXPECT_EQ(threaded.result.mesh.triangles(), serial.result.mesh.triangles()) << method;
    EXPECT_TRUE(threaded.result.mesh.points() == serial.result.mesh.points()) << method;
    EXPECT_EQ(threaded.result.summary.function_evaluations,
              serial.result.summary.function_evaluations);
    EXPECT_EQ(threaded.report.quality.centroid_distance.mean,
              serial.report.quality.centroid_distance.mean);  // summed in the same order
    EXPECT_EQ(threaded.report.quality.midpoint_distance.max,
              serial.report.quality.midpoint_distance.max);
    EXPECT_EQ(threaded.report.validation.report(), serial.report.validation.report());
  }
}

}  // namespace
}  // namespace tessera
