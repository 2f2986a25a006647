#include <algorithm>
#include <functional>
#include <limits>

#include "cone.hpp"

namespace rbla::conic::detail {

namespace {
double smallest_of(const std::vector<double>& values) {
  double smallest = std::numeric_limits<double>::infinity();
  for (double v : values) smallest = std::min(smallest, v);
  return smallest;
}
}  // namespace

ConeSet::ConeSet(Eigen::Index num_nonneg, const std::vector<Eigen::Index>& soc_dims,
                 ForkJoin* fork_join) {
  Eigen::Index offset = 0;
  if (num_nonneg > 0) {
    cones_.push_back(std::make_unique<NonnegativeCone>(0, num_nonneg));
    offset = num_nonneg;
  }
  // With a second thread and enough cones, the second-order cones are held as two halves, the
  // second of which the helper thread works on (the cones are independent of each other).
  constexpr std::size_t min_cones_to_split = 2000;
  const bool split = fork_join != nullptr && soc_dims.size() >= min_cones_to_split;
  const std::size_t half = split ? soc_dims.size() / 2 : soc_dims.size();
  if (half > 0) {
    const std::vector<Eigen::Index> first(soc_dims.begin(),
                                          soc_dims.begin() + static_cast<std::ptrdiff_t>(half));
    cones_.push_back(std::make_unique<SecondOrderCones>(offset, first));
    offset += cones_.back()->dim();
  }
  if (split) {
    const std::vector<Eigen::Index> second(soc_dims.begin() + static_cast<std::ptrdiff_t>(half),
                                           soc_dims.end());
    split_at_ = cones_.size();
    cones_.push_back(std::make_unique<SecondOrderCones>(offset, second));
    offset += cones_.back()->dim();
    fork_join_ = fork_join;
  }
  dim_ = offset;
  std::size_t packed = 0;
  for (const auto& cone : cones_) {
    degree_ += cone->degree();
    packed_offset_.push_back(packed);
    std::vector<ScalingBlock> blocks;
    cone->append_scaling_blocks(blocks);
    for (const ScalingBlock& block : blocks)
      packed += static_cast<std::size_t>(block.size * block.size);
  }
}

template <class F>
void ConeSet::for_each_cone(const F& f) const {
  if (!fork_join_) {
    for (std::size_t k = 0; k < cones_.size(); ++k) f(k);
    return;
  }
  const std::function<void()> first = [&] {
    for (std::size_t k = 0; k < split_at_; ++k) f(k);
  };
  const std::function<void()> second = [&] {
    for (std::size_t k = split_at_; k < cones_.size(); ++k) f(k);
  };
  fork_join_->run(first, second);
}

void ConeSet::set_identity(VecRef e) const {
  for (const auto& k : cones_) k->set_identity(e.segment(k->offset(), k->dim()));
}

bool ConeSet::update_scaling(const Vec& x, const Vec& z) {
  std::vector<char> ok(cones_.size(), 0);
  for_each_cone([&](std::size_t i) {
    const auto& k = cones_[i];
    ok[i] = k->update_scaling(x.segment(k->offset(), k->dim()), z.segment(k->offset(), k->dim()));
  });
  return std::all_of(ok.begin(), ok.end(), [](char v) { return v != 0; });
}

void ConeSet::lambda(Vec& out) const {
  out.resize(dim_);
  for_each_cone([&](std::size_t i) {
    const auto& k = cones_[i];
    k->lambda(out.segment(k->offset(), k->dim()));
  });
}

#define RBLA_CONE_APPLY(method)                                                        \
  void ConeSet::method(const Vec& v, Vec& out) const {                                 \
    out.resize(dim_);                                                                  \
    for_each_cone([&](std::size_t i) {                                                 \
      const auto& k = cones_[i];                                                       \
      k->method(v.segment(k->offset(), k->dim()), out.segment(k->offset(), k->dim())); \
    });                                                                                \
  }
RBLA_CONE_APPLY(mul_W)
RBLA_CONE_APPLY(mul_Winv)
RBLA_CONE_APPLY(mul_W2)
RBLA_CONE_APPLY(lambda_divide)
#undef RBLA_CONE_APPLY

void ConeSet::jordan_product(const Vec& a, const Vec& b, Vec& out) const {
  out.resize(dim_);
  for_each_cone([&](std::size_t i) {
    const auto& k = cones_[i];
    k->jordan_product(a.segment(k->offset(), k->dim()), b.segment(k->offset(), k->dim()),
                      out.segment(k->offset(), k->dim()));
  });
}

double ConeSet::max_step(const Vec& v, const Vec& dv) const {
  std::vector<double> steps(cones_.size());
  for_each_cone([&](std::size_t i) {
    const auto& k = cones_[i];
    steps[i] = k->max_step(v.segment(k->offset(), k->dim()), dv.segment(k->offset(), k->dim()));
  });
  return smallest_of(steps);
}

void ConeSet::centrality_correction(const Vec& v, double lo, double hi, Vec& out) const {
  out.resize(dim_);
  for_each_cone([&](std::size_t i) {
    const auto& k = cones_[i];
    k->centrality_correction(v.segment(k->offset(), k->dim()), lo, hi,
                             out.segment(k->offset(), k->dim()));
  });
}

double ConeSet::min_eigenvalue(const Vec& v) const {
  std::vector<double> values(cones_.size());
  for_each_cone([&](std::size_t i) {
    const auto& k = cones_[i];
    values[i] = k->min_eigenvalue(v.segment(k->offset(), k->dim()));
  });
  return smallest_of(values);
}

double ConeSet::max_step_from_lambda(const Vec& dv) const {
  std::vector<double> steps(cones_.size());
  for_each_cone([&](std::size_t i) {
    const auto& k = cones_[i];
    steps[i] = k->max_step_from_lambda(dv.segment(k->offset(), k->dim()));
  });
  return smallest_of(steps);
}

void ConeSet::append_steps_from_lambda(const Vec& dv, double limit, std::vector<double>& out) const {
  for (const auto& k : cones_) k->append_steps_from_lambda(dv.segment(k->offset(), k->dim()), limit, out);
}

std::vector<ScalingBlock> ConeSet::scaling_blocks() const {
  std::vector<ScalingBlock> blocks;
  for (const auto& k : cones_) k->append_scaling_blocks(blocks);
  return blocks;
}

void ConeSet::pack_W2(std::vector<double>& out) const {
  for_each_cone([&](std::size_t i) { cones_[i]->pack_W2(out.data() + packed_offset_[i]); });
}

}  // namespace rbla::conic::detail
