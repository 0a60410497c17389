// SPDX-License-Identifier: MIT
// What the atlas's open boundary holds, and when it lets go: the tangent bases of charts not
// yet finished (dropped when a chart is closed among closed neighbours, restored on demand), and
// the factorisations of queued charts within max_factorisation_bytes (a factorisation shared by
// several charts counted once). The queue itself.
#include <Eigen/Dense>
#include <algorithm>

#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/methods/atlas/atlas_builder.h"

namespace tessera::detail {

// (P T)ᵀ for the fixed view P (orthonormal rows, unfitted: the same for every chart).
Eigen::Matrix<double, 2, 3> AtlasBuilder::frame_signature(const Eigen::MatrixXd& T) const {
  Eigen::Matrix<double, 2, 3> signature;
  signature.row(0) = frame_view_(T.col(0)).transpose();
  signature.row(1) = frame_view_(T.col(1)).transpose();
  return signature;
}

// A retired chart's basis again: factored at its centre (one factorisation), then turned onto the
// old frame. With B = T'ᵀPᵀ for the new basis T' and S = TᵀPᵀ stored, T = T'Q where Qᵀ B = S,
// so Qᵀ = S Bᵀ(B Bᵀ)⁻¹, made exactly orthogonal by its polar factor.
void AtlasBuilder::restore_tangent(int c) const {
  Linearization linearization;
  TESSERA_CHECK(linearization.factor(problem_, center(c)),
                "atlas: the tangent plane of the chart at " << describe_point(center(c), *space_)
                                                           << " cannot be computed again");
  const Eigen::MatrixXd& restored = linearization.tangent_basis();
  const Eigen::Matrix<double, 2, 3> B = frame_signature(restored);
  const Eigen::Matrix2d Qt = frames_[c] * B.transpose() * (B * B.transpose()).inverse();
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(Qt, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix2d Q = (svd.matrixU() * svd.matrixV().transpose()).transpose();
  tangents_[c] = restored * Q;
  ++held_tangents_;
}

// Chart m is finished when it is closed (its polygon cut down to its disk by neighbours on every
// side) and so is every chart whose disk overlaps it: new charts are placed on the rims of open
// charts, so none will cut it again unless M comes back (then restore_tangent). Its basis, 2n
// numbers, is dropped. Checked around the chart c just processed.
void AtlasBuilder::retire_finished_charts(int c) {
  std::vector<int>& around = retire_around_;
  index_.candidates(center(c), charts_[c].radius, around);
  std::vector<int>& closed = retire_closed_;
  closed.clear();
  double largest = 0.0;
  for (int m : around) {
    if (tangents_[m].size() == 0 || charts_[m].queued || !is_closed(m) ||
        (m != c &&
         space_->distance(center(m), center(c)) >= charts_[m].radius + charts_[c].radius)) {
      continue;
    }
    closed.push_back(m);
    largest = std::max(largest, charts_[m].radius);
  }
  if (closed.empty()) {
    return;
  }
  // A chart j that overlaps some m above lies within R_c + 2·R_m + R_j of c: one query for all
  // of them, and of its charts only the open ones (the front, a few) are compared with each m.
  // (A query per m was a third of the build at n = 3.)
  std::vector<int>& open = retire_open_;
  index_.candidates(center(c), charts_[c].radius + 2.0 * largest, open);
  std::erase_if(open, [this](int j) { return !charts_[j].queued && is_closed(j); });
  for (int m : closed) {
    bool finished = true;
    for (int j : open) {
      if (j != m &&
          space_->distance(center(j), center(m)) < charts_[j].radius + charts_[m].radius) {
        finished = false;
        break;
      }
    }
    if (finished) {
      tangents_[m] = Eigen::MatrixXd();
      --held_tangents_;
    }
  }
}

// The queue is first in, first out: the newest chart is processed last, so it is the one whose
// factorisation is dropped when the budget is spent (the older ones are used sooner).
void AtlasBuilder::keep_factorisation(int c, Linearization&& linearization,
                                      const Eigen::MatrixXd& reference) {
  linearization.release_assembly();  // it waits for its solves: DF and the bordered matrix go
  // A factorisation already kept for another chart costs this one its point and basis only.
  // (Without sharing every entry holds its own, counted whole in the entry, as a checkpoint
  // stores it.)
  const void* identity = linearization.factorisation_identity();
  const auto shared =
      share_factorisations_ ? shared_factors_.find(identity) : shared_factors_.end();
  const std::size_t own_bytes =
      sizeof(double) * static_cast<std::size_t>(3 * rows_);  // point and basis
  const std::size_t bytes =
      shared != shared_factors_.end() ? own_bytes : linearization.memory_bytes();
  if (!factored_.empty() &&
      static_cast<double>(kept_bytes_ + bytes) > options_.max_factorisation_bytes) {
    ++refactored_charts_;
    return;  // refactored when the chart's turn comes
  }
  kept_bytes_ += bytes;
  std::size_t entry_bytes = bytes;
  if (share_factorisations_) {
    // The entry holds its point and basis; the factors are counted with their first holder.
    auto& factors = shared != shared_factors_.end()
                        ? shared->second
                        : shared_factors_.emplace(identity, SharedFactors{0, bytes - own_bytes})
                              .first->second;
    ++factors.holders;
    entry_bytes = own_bytes;
  }
  factored_.emplace(c, KeptFactorisation{std::move(linearization), entry_bytes, reference});
  note_boundary_bytes();
}

// Drops a kept entry from the count: its own bytes, and the shared factors' with their last
// holder.
void AtlasBuilder::forget_kept(std::unordered_map<int, KeptFactorisation>::iterator found) {
  kept_bytes_ -= found->second.bytes;
  const auto shared = shared_factors_.find(found->second.linearization.factorisation_identity());
  if (shared != shared_factors_.end() && --shared->second.holders == 0) {
    kept_bytes_ -= shared->second.bytes;
    shared_factors_.erase(shared);
  }
}

void AtlasBuilder::enqueue(int c) {
  charts_[c].queued = true;
  open_.push_back(c);
}

// The factorisation at chart c's centre: the one kept since c was made, else a new one guided
// by c's basis (its polygon's frame stays the stored basis). center_reference_ records the
// guide, so that a resumed build makes the same factorisation.
void AtlasBuilder::take_center_factorisation(int c, Linearization& at_center) {
  auto found = factored_.find(c);
  if (found != factored_.end()) {
    forget_kept(found);
    at_center = std::move(found->second.linearization);
    center_reference_ = std::move(found->second.reference);
    factored_.erase(found);
  } else {
    center_reference_ = tangent(c);
  }
  if (!at_center.is_factored()) {
    at_center.factor(problem_, center(c),
                     center_reference_.size() > 0 ? &center_reference_ : nullptr);
  }
}

}  // namespace tessera::detail
