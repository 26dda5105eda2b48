// The partition (domain/partition.h) over Zoltan's C interface: the only file that includes Zoltan.
#include "domain/partition.h"

#include <zoltan.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace polyfloe::domain {

namespace {

// Global ids: a 64-bit body id in two of Zoltan's 32-bit id words (ZOLTAN_ID_TYPE is unsigned int in Debian's build).
constexpr int kGidWords = 2;
static_assert(sizeof(ZOLTAN_ID_TYPE) == 4, "two Zoltan id words hold one body id");

void check(int code, const char* what) {
  if (code != ZOLTAN_OK && code != ZOLTAN_WARN)
    throw std::runtime_error(std::string("Zoltan: ") + what + " failed (error code " + std::to_string(code) + ")");
}

int count_items(void* data, int* ierr) {
  *ierr = ZOLTAN_OK;
  return static_cast<int>(static_cast<const std::vector<PartitionItem>*>(data)->size());
}

void list_items(void* data, int, int, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids, int, float* weights, int* ierr) {
  const auto& items = *static_cast<const std::vector<PartitionItem>*>(data);
  for (std::size_t k = 0; k < items.size(); ++k) {
    gids[kGidWords * k] = static_cast<ZOLTAN_ID_TYPE>(items[k].id >> 32);
    gids[kGidWords * k + 1] = static_cast<ZOLTAN_ID_TYPE>(items[k].id & 0xffffffffu);
    lids[k] = static_cast<ZOLTAN_ID_TYPE>(k);
    weights[k] = static_cast<float>(items[k].weight);
  }
  *ierr = ZOLTAN_OK;
}

int dimensions(void*, int* ierr) {
  *ierr = ZOLTAN_OK;
  return 2;
}

void coordinates(void* data, int, int, int count, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR lids, int, double* xy, int* ierr) {
  const auto& items = *static_cast<const std::vector<PartitionItem>*>(data);
  for (int k = 0; k < count; ++k) {
    const PartitionItem& it = items[lids[k]];
    xy[2 * k] = it.position.x();
    xy[2 * k + 1] = it.position.y();
  }
  *ierr = ZOLTAN_OK;
}

}  // namespace

struct Partition::Zoltan {
  Zoltan_Struct* zz = nullptr;
  ~Zoltan() {
    if (zz) Zoltan_Destroy(&zz);
  }
};

Partition::Partition(MPI_Comm comm) : comm_(comm), zoltan_(std::make_unique<Zoltan>()) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &ranks_);
  float version = 0.0f;
  check(Zoltan_Initialize(0, nullptr, &version), "Zoltan_Initialize");
  zoltan_->zz = Zoltan_Create(comm_);
  if (!zoltan_->zz) throw std::runtime_error("Zoltan: Zoltan_Create failed");
  Zoltan_Struct* zz = zoltan_->zz;
  const std::pair<const char*, const char*> params[] = {
      {"DEBUG_LEVEL", "0"},     {"LB_METHOD", "RCB"},      {"NUM_GID_ENTRIES", "2"},
      {"NUM_LID_ENTRIES", "1"}, {"OBJ_WEIGHT_DIM", "1"},   {"RETURN_LISTS", "NONE"},
      {"KEEP_CUTS", "1"},       {"RCB_OUTPUT_LEVEL", "0"}, {"IMBALANCE_TOL", "1.05"}};
  for (const auto& [name, value] : params) check(Zoltan_Set_Param(zz, name, value), name);
  void* data = &items_;
  check(Zoltan_Set_Num_Obj_Fn(zz, count_items, data), "Zoltan_Set_Num_Obj_Fn");
  check(Zoltan_Set_Obj_List_Fn(zz, list_items, data), "Zoltan_Set_Obj_List_Fn");
  check(Zoltan_Set_Num_Geom_Fn(zz, dimensions, data), "Zoltan_Set_Num_Geom_Fn");
  check(Zoltan_Set_Geom_Multi_Fn(zz, coordinates, data), "Zoltan_Set_Geom_Multi_Fn");
}

Partition::~Partition() = default;

std::vector<int> Partition::balance(std::span<const PartitionItem> items) {
  items_.assign(items.begin(), items.end());
  std::vector<int> to(items.size(), rank_);
  long long local = static_cast<long long>(items.size()), total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LONG_LONG, MPI_SUM, comm_);
  if (total == 0) {  // nothing to cut: the queries answer rank 0 until there is
    has_cuts_ = false;
    return to;
  }
  int changes = 0, gid_words = 0, lid_words = 0, n_import = 0, n_export = 0;
  ZOLTAN_ID_PTR import_gids = nullptr, import_lids = nullptr, export_gids = nullptr, export_lids = nullptr;
  int *import_procs = nullptr, *import_parts = nullptr, *export_procs = nullptr, *export_parts = nullptr;
  const int code = Zoltan_LB_Partition(zoltan_->zz, &changes, &gid_words, &lid_words, &n_import, &import_gids,
                                       &import_lids, &import_procs, &import_parts, &n_export, &export_gids,
                                       &export_lids, &export_procs, &export_parts);
  Zoltan_LB_Free_Part(&import_gids, &import_lids, &import_procs, &import_parts);
  Zoltan_LB_Free_Part(&export_gids, &export_lids, &export_procs, &export_parts);
  items_.clear();
  check(code, "Zoltan_LB_Partition (recursive coordinate bisection)");
  has_cuts_ = true;
  // Each item to the rank whose region holds its centroid, by the kept cuts: the one rule of ownership (RCB itself
  // may put items that lie exactly on a cut on either side, to balance them).
  for (std::size_t k = 0; k < items.size(); ++k) to[k] = rank_of(items[k].position);
  return to;
}

int Partition::rank_of(const geometry::Vec2& p) const {
  if (!has_cuts_) return 0;
  double xy[3] = {p.x(), p.y(), 0.0};
  int rank = 0;
  check(Zoltan_LB_Point_Assign(zoltan_->zz, xy, &rank), "Zoltan_LB_Point_Assign");
  return rank;
}

void Partition::ranks_of(const geometry::Aabb& box, std::vector<int>& out) const {
  out.clear();
  if (!has_cuts_) {
    out.push_back(0);
    return;
  }
  out.resize(static_cast<std::size_t>(ranks_));
  int count = 0;
  check(Zoltan_LB_Box_Assign(zoltan_->zz, box.lo.x(), box.lo.y(), 0.0, box.hi.x(), box.hi.y(), 0.0, out.data(), &count),
        "Zoltan_LB_Box_Assign");
  out.resize(static_cast<std::size_t>(count));
  std::sort(out.begin(), out.end());
}

void weigh_by_cost(std::span<PartitionItem> items, std::span<const int> pairs, double busy) {
  if (items.size() != pairs.size()) throw std::logic_error("weigh_by_cost: one pair count per item");
  double units = 0.0;
  for (const int p : pairs) units += 1.0 + p;
  // [us] (Zoltan's weights are floats); a rank that measured nothing still weighs its floes, by a nanosecond
  const double scale = units > 0.0 ? 1e6 * std::max(busy, 1e-9) / units : 0.0;
  for (std::size_t k = 0; k < items.size(); ++k) items[k].weight = scale * (1.0 + pairs[k]);
}

Load measured_load(MPI_Comm comm, double busy) {
  // Every rank's time, summed in rank order on every rank: the same bits everywhere (a reduction's sum of doubles
  // need not be), so that the ranks' decisions on it agree.
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  std::vector<double> all(static_cast<std::size_t>(ranks), 0.0);
  MPI_Allgather(&busy, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, comm);
  Load load;
  double sum = 0.0;
  for (const double b : all) {
    load.largest = std::max(load.largest, b);
    sum += b;
  }
  load.mean = sum / ranks;
  return load;
}

}  // namespace polyfloe::domain
