// SPDX-License-Identifier: MIT
// A decorator that counts evaluations of F and of its Jacobian, and the factorisations of the
// Jacobian made by Linearization, for summaries and benchmarks.
#pragma once

#include "tessera/core/ambient_space.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/jacobian_product.h"
#include "tessera/core/linearization_backend.h"

namespace tessera {

/// Work done on a problem: evaluations of F and of DF, and numerical factorisations of DF (or of
/// the bordered matrix [DF; border]). The currency of continuation at large n.
struct WorkCounts {
  long function_evaluations = 0;
  long jacobian_evaluations = 0;
  long factorisations = 0;
  WorkCounts operator-(const WorkCounts& other) const {
    return {function_evaluations - other.function_evaluations,
            jacobian_evaluations - other.jacobian_evaluations,
            factorisations - other.factorisations};
  }
  WorkCounts& operator+=(const WorkCounts& other) {
    function_evaluations += other.function_evaluations;
    jacobian_evaluations += other.jacobian_evaluations;
    factorisations += other.factorisations;
    return *this;
  }
};

/// Forwards to `inner` and counts calls. Methods wrap the user's problem in one of these.
class CountedProblem final : public ImplicitProblem {
 public:
  explicit CountedProblem(const ImplicitProblem& inner) : inner_(inner) {}
  CountedProblem(const CountedProblem&) = delete;  // counted_products_ refers to this one
  CountedProblem& operator=(const CountedProblem&) = delete;

  int ambient_dimension() const override { return inner_.ambient_dimension(); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    ++function_evaluations_;
    inner_.evaluate(x, F);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    ++jacobian_evaluations_;
    inner_.jacobian(x, J);
  }
  bool has_sparse_jacobian() const override { return inner_.has_sparse_jacobian(); }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override {
    ++jacobian_evaluations_;
    inner_.sparse_jacobian(x, J);
  }
  std::string name() const override { return inner_.name(); }
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
  void record_jacobian_evaluations(long count) const { jacobian_evaluations_ += count; }

  /// Called by Linearization::factor with the factorisations it made for this problem and the
  /// wall time they took (evaluating DF, bordering, analysing and factoring).
  void record_factorisations(long count, double seconds) const {
    factorisations_ += count;
    factorisation_seconds_ += seconds;
  }
  double factorisation_seconds() const { return factorisation_seconds_; }

  long function_evaluations() const { return function_evaluations_; }
  long jacobian_evaluations() const { return jacobian_evaluations_; }
  long factorisations() const { return factorisations_; }
  WorkCounts counts() const {
    return {function_evaluations_, jacobian_evaluations_, factorisations_};
  }

 private:
  // The inner problem's DF(y)·V, each product counted as an evaluation of DF.
  class CountedProducts final : public JacobianProduct {
   public:
    explicit CountedProducts(const CountedProblem& owner) : owner_(owner) {}
    double evaluate_jacobian_at(const Eigen::Ref<const Eigen::VectorXd>& y) const override {
      ++owner_.jacobian_evaluations_;
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
  mutable long function_evaluations_ = 0;
  mutable long jacobian_evaluations_ = 0;
  mutable long factorisations_ = 0;
  mutable double factorisation_seconds_ = 0.0;
};

}  // namespace tessera
