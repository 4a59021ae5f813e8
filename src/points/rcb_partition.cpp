// zoltan.h includes mpi.h; only the C API is used (Open MPI's C++ bindings need their own library).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include "points/rcb_partition.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include <mpi.h>
#include <zoltan.h>

namespace ballista {

struct RcbPartition::Impl {
  Zoltan_Struct* zz = nullptr;
  // The points handed to Zoltan during a partition call (its query callbacks read them).
  const Vec3* x = nullptr;
  const std::int64_t* ids = nullptr;
  Index n = 0;
  int dim = 3;
};

namespace {

int num_obj(void* data, int* ierr) {
  *ierr = ZOLTAN_OK;
  return static_cast<int>(static_cast<RcbPartition::Impl*>(data)->n);
}

void obj_list(void* data, int, int, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids, int, float*, int* ierr) {
  const auto* d = static_cast<RcbPartition::Impl*>(data);
  for (Index p = 0; p < d->n; ++p) {
    gids[p] = static_cast<ZOLTAN_ID_TYPE>(d->ids[p]);
    lids[p] = static_cast<ZOLTAN_ID_TYPE>(p);
  }
  *ierr = ZOLTAN_OK;
}

int num_geom(void* data, int* ierr) {
  *ierr = ZOLTAN_OK;
  return static_cast<RcbPartition::Impl*>(data)->dim;
}

void geom_multi(void* data, int, int, int num, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR lids, int dim, double* out, int* ierr) {
  const auto* d = static_cast<RcbPartition::Impl*>(data);
  for (int k = 0; k < num; ++k)
    for (int a = 0; a < dim; ++a) out[k * dim + a] = d->x[lids[k]][a];
  *ierr = ZOLTAN_OK;
}

void zcheck(int rc, const char* what) {
  if (rc != ZOLTAN_OK && rc != ZOLTAN_WARN) throw std::runtime_error(std::string("Zoltan call failed: ") + what);
}

}  // namespace

RcbPartition::RcbPartition(const Communicator& comm, int dim)
    : impl_(std::make_unique<Impl>()), comm_(comm), dim_(dim) {
  impl_->dim = dim;
  if (!comm.distributed()) return;
  float version = 0.0f;
  zcheck(Zoltan_Initialize(0, nullptr, &version), "Zoltan_Initialize");
  MPI_Comm c;
  const std::uintptr_t h = comm.native_handle();
  std::memcpy(&c, &h, sizeof c);
  impl_->zz = Zoltan_Create(c);
  Zoltan_Struct* zz = impl_->zz;
  Zoltan_Set_Param(zz, "DEBUG_LEVEL", "0");
  Zoltan_Set_Param(zz, "LB_METHOD", "RCB");
  Zoltan_Set_Param(zz, "NUM_GID_ENTRIES", "1");
  Zoltan_Set_Param(zz, "NUM_LID_ENTRIES", "1");
  Zoltan_Set_Param(zz, "OBJ_WEIGHT_DIM", "0");  // unit weights: balance the point count
  Zoltan_Set_Param(zz, "RETURN_LISTS", "PARTS");
  Zoltan_Set_Param(zz, "KEEP_CUTS", "1");        // owner() of any position after the partition
  Zoltan_Set_Param(zz, "IMBALANCE_TOL", "1.02");
  Zoltan_Set_Num_Obj_Fn(zz, num_obj, impl_.get());
  Zoltan_Set_Obj_List_Fn(zz, obj_list, impl_.get());
  Zoltan_Set_Num_Geom_Fn(zz, num_geom, impl_.get());
  Zoltan_Set_Geom_Multi_Fn(zz, geom_multi, impl_.get());
}

RcbPartition::~RcbPartition() {
  if (impl_ && impl_->zz) Zoltan_Destroy(&impl_->zz);
}

std::vector<int> RcbPartition::partition(const Vec3* x, const std::int64_t* ids, Index n) {
  std::vector<int> dest(static_cast<std::size_t>(n), comm_.rank());
  if (!comm_.distributed()) {
    ready_ = true;
    return dest;
  }
  impl_->x = x;
  impl_->ids = ids;
  impl_->n = n;
  int changes = 0, ngid = 0, nlid = 0, nimp = 0, nexp = 0;
  ZOLTAN_ID_PTR igid = nullptr, ilid = nullptr, egid = nullptr, elid = nullptr;
  int *iproc = nullptr, *ipart = nullptr, *eproc = nullptr, *epart = nullptr;
  // Fewer points than ranks cannot be cut into a part per rank: everything stays where it is
  // (and, before any partition, owner() keeps every point on its rank).
  if (comm_.sum(static_cast<std::int64_t>(n)) < comm_.size()) return dest;
  const int rc = Zoltan_LB_Partition(impl_->zz, &changes, &ngid, &nlid, &nimp, &igid, &ilid, &iproc, &ipart, &nexp,
                                     &egid, &elid, &eproc, &epart);
  const bool ok = rc == ZOLTAN_OK || rc == ZOLTAN_WARN;
  // RETURN_LISTS = PARTS: the export list holds every local object with its new part (= rank).
  if (ok)
    for (int k = 0; k < nexp; ++k) dest[elid[k]] = epart[k];
  Zoltan_LB_Free_Part(&igid, &ilid, &iproc, &ipart);
  Zoltan_LB_Free_Part(&egid, &elid, &eproc, &epart);
  impl_->x = nullptr;
  impl_->ids = nullptr;
  impl_->n = 0;
  // Every rank learns whether any failed, so that all keep their points together (a rank that
  // threw alone would leave the others waiting in the next exchange).
  if (comm_.any(!ok)) {
    std::fill(dest.begin(), dest.end(), comm_.rank());
    return dest;
  }
  // Every rank's region box, from the kept cuts (the outer faces are Zoltan's +-DBL_MAX).
  boxes_.assign(static_cast<std::size_t>(6 * comm_.size()), 0.0);
  for (int r = 0; r < comm_.size(); ++r) {
    int ndim = 0;
    double* b = boxes_.data() + 6 * r;
    zcheck(Zoltan_RCB_Box(impl_->zz, r, &ndim, b, b + 1, b + 2, b + 3, b + 4, b + 5), "Zoltan_RCB_Box");
  }
  ready_ = true;
  ++partitions_;
  return dest;
}

void RcbPartition::restore_boxes(const std::vector<double>& boxes) {
  if (!comm_.distributed()) return;
  if (boxes.size() != static_cast<std::size_t>(6 * comm_.size()))
    throw std::runtime_error("restore_boxes: " + std::to_string(boxes.size() / 6) + " region boxes for " +
                             std::to_string(comm_.size()) + " ranks");
  boxes_ = boxes;
  ready_ = true;
}

std::vector<int> RcbPartition::neighbours(double margin) const {
  std::vector<int> out;
  if (!ready_ || boxes_.empty()) return out;
  const double* mine = boxes_.data() + 6 * comm_.rank();
  for (int r = 0; r < comm_.size(); ++r) {
    if (r == comm_.rank()) continue;
    const double* b = boxes_.data() + 6 * r;
    bool overlap = true;
    for (int a = 0; a < dim_; ++a)  // [lo - m, hi + m] of both: they overlap if the gap is below 2 m
      overlap = overlap && b[a] - margin <= mine[3 + a] + margin && mine[a] - margin <= b[3 + a] + margin;
    if (overlap) out.push_back(r);
  }
  return out;
}

int RcbPartition::owner(const Vec3& x) const {
  if (!comm_.distributed()) return 0;
  if (!ready_) return comm_.rank();
  // Half-open boxes [lo, hi): a point on a cut belongs to the upper side. Own box first: almost
  // every particle stays where it was.
  auto inside = [&](int r) {
    const double* b = boxes_.data() + 6 * r;
    for (int a = 0; a < dim_; ++a)
      if (!(x[a] >= b[a] && x[a] < b[3 + a])) return false;
    return true;
  };
  if (inside(comm_.rank())) return comm_.rank();
  for (int r = 0; r < comm_.size(); ++r)
    if (inside(r)) return r;
  return comm_.rank();  // outside every box (beyond +-DBL_MAX, or NaN: the solver reports it)
}

void RcbPartition::owners(const Vec3* x, Index n, std::vector<int>& out) const {
  out.resize(static_cast<std::size_t>(n));
  for (Index p = 0; p < n; ++p) out[p] = owner(x[p]);
}

}  // namespace ballista
