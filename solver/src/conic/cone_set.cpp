#include <algorithm>
#include <limits>

#include "cone.hpp"

namespace rbla::conic::detail {

ConeSet::ConeSet(Eigen::Index num_nonneg, const std::vector<Eigen::Index>& soc_dims) {
  Eigen::Index offset = 0;
  if (num_nonneg > 0) {
    cones_.push_back(std::make_unique<NonnegativeCone>(0, num_nonneg));
    offset = num_nonneg;
  }
  if (!soc_dims.empty()) {
    cones_.push_back(std::make_unique<SecondOrderCones>(offset, soc_dims));
    offset += cones_.back()->dim();
  }
  dim_ = offset;
  for (const auto& cone : cones_) degree_ += cone->degree();
}

void ConeSet::set_identity(VecRef e) const {
  for (const auto& k : cones_) k->set_identity(e.segment(k->offset(), k->dim()));
}

bool ConeSet::update_scaling(const Vec& x, const Vec& z) {
  for (const auto& k : cones_) {
    if (!k->update_scaling(x.segment(k->offset(), k->dim()), z.segment(k->offset(), k->dim()))) {
      return false;
    }
  }
  return true;
}

void ConeSet::lambda(Vec& out) const {
  out.resize(dim_);
  for (const auto& k : cones_) k->lambda(out.segment(k->offset(), k->dim()));
}

#define RBLA_CONE_APPLY(method)                                                        \
  void ConeSet::method(const Vec& v, Vec& out) const {                                 \
    out.resize(dim_);                                                                  \
    for (const auto& k : cones_) {                                                     \
      k->method(v.segment(k->offset(), k->dim()), out.segment(k->offset(), k->dim())); \
    }                                                                                  \
  }
RBLA_CONE_APPLY(mul_W)
RBLA_CONE_APPLY(mul_Winv)
RBLA_CONE_APPLY(mul_W2)
RBLA_CONE_APPLY(lambda_divide)
#undef RBLA_CONE_APPLY

void ConeSet::jordan_product(const Vec& a, const Vec& b, Vec& out) const {
  out.resize(dim_);
  for (const auto& k : cones_) {
    k->jordan_product(a.segment(k->offset(), k->dim()), b.segment(k->offset(), k->dim()),
                      out.segment(k->offset(), k->dim()));
  }
}

double ConeSet::max_step(const Vec& v, const Vec& dv) const {
  double step = std::numeric_limits<double>::infinity();
  for (const auto& k : cones_) {
    step = std::min(
        step, k->max_step(v.segment(k->offset(), k->dim()), dv.segment(k->offset(), k->dim())));
  }
  return step;
}

void ConeSet::centrality_correction(const Vec& v, double lo, double hi, Vec& out) const {
  out.resize(dim_);
  for (const auto& k : cones_) {
    k->centrality_correction(v.segment(k->offset(), k->dim()), lo, hi,
                             out.segment(k->offset(), k->dim()));
  }
}

double ConeSet::min_eigenvalue(const Vec& v) const {
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& k : cones_) smallest = std::min(smallest, k->min_eigenvalue(v.segment(k->offset(), k->dim())));
  return smallest;
}

double ConeSet::max_step_from_lambda(const Vec& dv) const {
  double step = std::numeric_limits<double>::infinity();
  for (const auto& k : cones_) {
    step = std::min(step, k->max_step_from_lambda(dv.segment(k->offset(), k->dim())));
  }
  return step;
}

std::vector<ScalingBlock> ConeSet::scaling_blocks() const {
  std::vector<ScalingBlock> blocks;
  for (const auto& k : cones_) k->append_scaling_blocks(blocks);
  return blocks;
}

void ConeSet::pack_W2(std::vector<double>& out) const {
  double* cursor = out.data();
  for (const auto& k : cones_) cursor = k->pack_W2(cursor);
}

}  // namespace rbla::conic::detail
