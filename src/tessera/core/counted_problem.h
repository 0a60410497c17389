// SPDX-License-Identifier: MIT
// A decorator that counts evaluations of F and of its Jacobian, and the factorisations of the
// Jacobian made by Linearization, for summaries and benchmarks.
#pragma once

#include <array>
#include <atomic>
#include <cmath>

#include "tessera/core/ambient_space.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/jacobian_product.h"
#include "tessera/core/linearization_backend.h"

namespace tessera {

/// Work done on a problem: evaluations of F and of DF, numerical factorisations of DF (or of
/// the bordered matrix [DF; border]), and solves with them. The currency of continuation at
/// large n: where factorisations are shared (issue 30) the solves are the rest of the cost.
struct WorkCounts {
  long function_evaluations = 0;
  long jacobian_evaluations = 0;
  long factorisations = 0;
  /// Right-hand sides solved with a factorisation (own or borrowed): a solve of k columns at
  /// once counts k (one sweep over the factors serves them all, at less than k times the cost).
  long solves = 0;
  WorkCounts operator-(const WorkCounts& other) const {
    return {function_evaluations - other.function_evaluations,
            jacobian_evaluations - other.jacobian_evaluations,
            factorisations - other.factorisations, solves - other.solves};
  }
  WorkCounts& operator+=(const WorkCounts& other) {
    function_evaluations += other.function_evaluations;
    jacobian_evaluations += other.jacobian_evaluations;
    factorisations += other.factorisations;
    solves += other.solves;
    return *this;
  }
};

/// A count that several threads add to at once (the loops of parallel_for.h evaluate F on
/// threads): each thread adds to a slot of its own, on its own cache line, so that counting
/// costs no contention; the total sums the slots. Integers, so the total is exact in any order.
class ConcurrentCount {
 public:
  void add(long amount) { slots_[slot()].value.fetch_add(amount, std::memory_order_relaxed); }
  long total() const {
    long sum = 0;
    for (const Slot& slot : slots_) {
      sum += slot.value.load(std::memory_order_relaxed);
    }
    return sum;
  }

 private:
  static constexpr std::size_t kSlots = 64;  // threads beyond share slots (atomically still)
  struct alignas(64) Slot {
    std::atomic<long> value{0};
  };
  // This thread's slot: threads are numbered on their first count, in any counter.
  static std::size_t slot() {
    static std::atomic<std::size_t> next{0};
    thread_local const std::size_t mine = next.fetch_add(1, std::memory_order_relaxed) % kSlots;
    return mine;
  }
  std::array<Slot, kSlots> slots_;
};

/// Forwards to `inner` and counts calls. Methods wrap the user's problem in one of these.
/// Thread-safe when `inner` is: the counts are ConcurrentCounts.
class CountedProblem final : public ImplicitProblem {
 public:
  explicit CountedProblem(const ImplicitProblem& inner) : inner_(inner) {}
  CountedProblem(const CountedProblem&) = delete;  // counted_products_ refers to this one
  CountedProblem& operator=(const CountedProblem&) = delete;

  int ambient_dimension() const override { return inner_.ambient_dimension(); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    function_evaluations_.add(1);
    inner_.evaluate(x, F);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    jacobian_evaluations_.add(1);
    inner_.jacobian(x, J);
  }
  bool has_sparse_jacobian() const override { return inner_.has_sparse_jacobian(); }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override {
    jacobian_evaluations_.add(1);
    inner_.sparse_jacobian(x, J);
  }
  std::string name() const override { return inner_.name(); }
  bool is_thread_safe() const override { return inner_.is_thread_safe(); }
  std::vector<std::string> coordinate_names() const override { return inner_.coordinate_names(); }
  std::vector<CoordinateBlock> coordinate_blocks() const override {
    return inner_.coordinate_blocks();
  }
  std::optional<Dynamics> dynamics() const override { return inner_.dynamics(); }
  std::shared_ptr<const AmbientSpace> space() const override { return inner_.space(); }
  std::unique_ptr<LinearizationBackend> make_linearization_backend() const override {
    return inner_.make_linearization_backend();
  }
  const JacobianProduct* as_jacobian_product() const override {
    return inner_.as_jacobian_product() != nullptr ? &counted_products_ : nullptr;
  }
  /// Called by Linearization::factor for the evaluations of DF that a problem's own backend
  /// made without calling `jacobian` (the PETSc backend evaluates DF on distributed matrices).
  void record_jacobian_evaluations(long count) const { jacobian_evaluations_.add(count); }

  /// Called by Linearization::factor with the factorisations it made for this problem and the
  /// wall time they took (evaluating DF, bordering, analysing and factoring).
  void record_factorisations(long count, double seconds) const {
    factorisations_.add(count);
    factorisation_nanoseconds_.add(std::lround(seconds * 1e9));
  }
  /// Called by Linearization's solves with the right-hand sides (columns) they solved.
  void record_solves(long columns) const { solves_.add(columns); }
  /// Summed over the threads that factored (CPU time, not wall time, when they overlap).
  double factorisation_seconds() const { return 1e-9 * factorisation_nanoseconds_.total(); }

  long function_evaluations() const { return function_evaluations_.total(); }
  long jacobian_evaluations() const { return jacobian_evaluations_.total(); }
  long factorisations() const { return factorisations_.total(); }
  long solves() const { return solves_.total(); }
  WorkCounts counts() const {
    return {function_evaluations(), jacobian_evaluations(), factorisations(), solves()};
  }

 private:
  // The inner problem's DF(y)·V, each product counted as an evaluation of DF.
  class CountedProducts final : public JacobianProduct {
   public:
    explicit CountedProducts(const CountedProblem& owner) : owner_(owner) {}
    double evaluate_jacobian_at(const Eigen::Ref<const Eigen::VectorXd>& y) const override {
      owner_.jacobian_evaluations_.add(1);
      return owner_.inner_.as_jacobian_product()->evaluate_jacobian_at(y);
    }
    void multiply_jacobian(const Eigen::Ref<const Eigen::MatrixXd>& V,
                           Eigen::MatrixXd& JV) const override {
      owner_.inner_.as_jacobian_product()->multiply_jacobian(V, JV);
    }

   private:
    const CountedProblem& owner_;
  };

  const ImplicitProblem& inner_;
  CountedProducts counted_products_{*this};
  mutable ConcurrentCount function_evaluations_;
  mutable ConcurrentCount jacobian_evaluations_;
  mutable ConcurrentCount factorisations_;
  mutable ConcurrentCount solves_;
  mutable ConcurrentCount factorisation_nanoseconds_;
};

}  // namespace tessera
