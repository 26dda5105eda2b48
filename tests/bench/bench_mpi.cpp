// The World cut among MPI ranks (domain::DistributedWorld) on the dense pack of bench_step: time per floe-step,
// and each rank's communication per step (bytes and messages of the step's exchanges, the seconds spent in them,
// waiting for the neighbours included, in the renewals of the halo and in the per-step test for one). A benchmark
// driver, not Google Benchmark: it runs under mpirun, prints a table and writes JSON.
//
//   mpirun -np R build/tests/bench_mpi [--floes N] [--per-rank] [--steps S] [--threads T] [--contact-only]
//                                      [--lattice-order] [--margin M] [-o FILE.json]
//
// The pack: tsupport::make_pack(N, seed 7), jammed inside four fixed walls (~4 contacts per floe), added in random
// order unless --lattice-order, every default drift term on unless --contact-only (as bench_step's BM_DensePack and
// BM_DensePackContactOnly); --per-rank makes it N x R floes (weak scaling). dt = the shortest contact duration at
// 1 m/s / 40. Two warm steps, then S timed steps between barriers: wall time per step, and per floe-step
// (wall x R x T / (S x floes): core-microseconds, 1 rank on 1 thread is the serial figure). On this 2-core machine
// R x T up to 2 is meaningful; more ranks are oversubscribed (correct, not timed).
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "dense_pack.h"
#include "domain/distributed_world.h"
#include "driver_args.h"
#include "dynamics/world.h"
#include "forcing/analytic_fields.h"
#include "json_out.h"

using namespace polyfloe;

namespace {

struct Options {
  int floes = 15000;
  bool per_rank = false;
  int steps = 20;
  int threads = 1;
  bool contact_only = false;
  bool lattice_order = false;
  double margin = 0.0;  // [m], 0: DistributedWorld's default
  std::string out;
};

dynamics::WorldSettings settings(const Options& o) {
  dynamics::WorldSettings ws;
  ws.store_in_space_order = true;
  ws.drift.ocean = forcing::make_field(forcing::FieldSpec::uniform({0.2, 0.05}));
  ws.drift.wind = forcing::make_field(forcing::FieldSpec::uniform({8.0, 6.0}));
  if (o.contact_only)
    ws.drift.form_drag = ws.drift.moment_drag = ws.drift.skin_drag = ws.drift.air_drag = ws.drift.coriolis = false;
  return ws;
}

// Each rank's figures, gathered on rank 0 (one row per rank).
struct RankRow {
  double owned, ghosts, halo_bytes, halo_messages, halo_s, renewal_bytes, renewal_s, check_s, renewals, migrated;
};

int run(const Options& o, int rank, int ranks) {
  const int n = o.per_rank ? o.floes * ranks : o.floes;
  tsupport::PackSpec ps;
  ps.shuffle = !o.lattice_order;
  const auto t_gen = std::chrono::steady_clock::now();
  const tsupport::Pack pack = tsupport::make_pack(n, ps, 7u);
  const dynamics::WorldSettings ws = settings(o);
  domain::DistributedWorld dw(MPI_COMM_WORLD, ws, pack.bodies, o.margin);
  dw.set_threads(o.threads);
  double dt = dw.local().size() > 0 ? dw.local().shortest_contact_duration(1.0) / 40.0 : 1.0, shortest = 0.0;
  MPI_Allreduce(&dt, &shortest, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  dt = shortest;
  const double setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_gen).count();
  for (int k = 0; k < 2; ++k) dw.step(dt);
  const domain::DistributedWorld::Communication c0 = dw.communication();
  const std::uint64_t renewals0 = dw.renewals(), migrated0 = dw.migrated();
  MPI_Barrier(MPI_COMM_WORLD);
  const auto t0 = std::chrono::steady_clock::now();
  std::uint64_t contacts = 0;
  for (int k = 0; k < o.steps; ++k) {
    dw.step(dt);
    contacts += dw.local().contact_count();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const domain::DistributedWorld::Communication c1 = dw.communication();
  const dynamics::World& w = dw.local();
  std::size_t owned = 0;
  for (int i = 0; i < static_cast<int>(w.size()); ++i) owned += !w.is_ghost(i);
  const double per_step = 1.0 / o.steps;
  const RankRow mine{static_cast<double>(owned),
                     static_cast<double>(w.size() - owned),
                     static_cast<double>(c1.halo_bytes - c0.halo_bytes) * per_step,
                     static_cast<double>(c1.halo_messages - c0.halo_messages) * per_step,
                     (c1.halo_seconds - c0.halo_seconds) * per_step,
                     static_cast<double>(c1.renewal_bytes - c0.renewal_bytes) * per_step,
                     (c1.renewal_seconds - c0.renewal_seconds) * per_step,
                     (c1.check_seconds - c0.check_seconds) * per_step,
                     static_cast<double>(dw.renewals() - renewals0),
                     static_cast<double>(dw.migrated() - migrated0)};
  std::vector<RankRow> rows(static_cast<std::size_t>(ranks));
  MPI_Gather(&mine, sizeof mine, MPI_BYTE, rows.data(), sizeof mine, MPI_BYTE, 0, MPI_COMM_WORLD);
  std::uint64_t all_contacts = 0;
  MPI_Reduce(&contacts, &all_contacts, 1, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
  if (rank != 0) return 0;

  const double floe_steps = static_cast<double>(o.steps) * pack.floes;
  const double us = 1e6 * wall * ranks * o.threads / floe_steps;
  std::printf("bench_mpi: %d floes (%s order, %s), %d ranks x %d threads, dt %.3g ms, %d steps, setup %.1f s\n",
              pack.floes, o.lattice_order ? "lattice" : "random", o.contact_only ? "contact only" : "all drift terms",
              ranks, o.threads, 1e3 * dt, o.steps, setup_s);
  std::printf("  wall %.3f ms per step; %.3f core-us per floe-step (wall x ranks x threads); %.2f contacts per floe\n",
              1e3 * wall / o.steps, us, 2.0 * static_cast<double>(all_contacts) / floe_steps);
  std::printf("  %4s %8s %7s %12s %8s %10s %12s %10s %10s %8s %8s\n", "rank", "owned", "ghosts", "halo B/step",
              "msg/step", "halo ms", "renew B/step", "renew ms", "check ms", "renewals", "migrated");
  tsupport::Json j;
  j["floes"] = pack.floes;
  j["ranks"] = ranks;
  j["threads"] = o.threads;
  j["order"] = o.lattice_order ? "lattice" : "random";
  j["contact_only"] = o.contact_only;
  j["steps"] = o.steps;
  j["dt_s"] = dt;
  j["wall_s_per_step"] = wall / o.steps;
  j["core_us_per_floe_step"] = us;
  j["contacts_per_floe"] = 2.0 * static_cast<double>(all_contacts) / floe_steps;
  j["margin_m"] = dw.margin();
  j["ranks_rows"] = tsupport::Json::array();
  for (int q = 0; q < ranks; ++q) {
    const RankRow& r = rows[static_cast<std::size_t>(q)];
    std::printf("  %4d %8.0f %7.0f %12.0f %8.1f %10.3f %12.0f %10.3f %10.3f %8.0f %8.0f\n", q, r.owned, r.ghosts,
                r.halo_bytes, r.halo_messages, 1e3 * r.halo_s, r.renewal_bytes, 1e3 * r.renewal_s, 1e3 * r.check_s,
                r.renewals, r.migrated);
    j["ranks_rows"].push_back({{"owned", r.owned},
                               {"ghosts", r.ghosts},
                               {"halo_bytes_per_step", r.halo_bytes},
                               {"halo_messages_per_step", r.halo_messages},
                               {"halo_s_per_step", r.halo_s},
                               {"renewal_bytes_per_step", r.renewal_bytes},
                               {"renewal_s_per_step", r.renewal_s},
                               {"check_s_per_step", r.check_s},
                               {"renewals", r.renewals},
                               {"migrated", r.migrated}});
  }
  if (!o.out.empty() && !tsupport::write_json(o.out, j)) return 1;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  Options o;
  CLI::App app("The World cut among MPI ranks on the dense pack: time per floe-step and communication", "bench_mpi");
  app.add_option("--floes", o.floes, "floes in the pack (per rank with --per-rank)")
      ->capture_default_str()
      ->check(CLI::Range(10, 10000000));
  app.add_flag("--per-rank", o.per_rank, "the pack has floes x ranks floes (weak scaling)");
  app.add_option("--steps", o.steps, "timed steps")->capture_default_str()->check(CLI::Range(1, 1000000));
  app.add_option("--threads", o.threads, "OpenMP threads per rank")->capture_default_str()->check(CLI::Range(1, 256));
  app.add_flag("--contact-only", o.contact_only, "every drift term off (the contact dynamics alone)");
  app.add_flag("--lattice-order", o.lattice_order, "bodies added in lattice order (default: random order)");
  app.add_option("--margin", o.margin, "the halo's margin [m] (default: 0.5 x the mean equivalent radius)")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("-o", o.out, "the JSON file written (rank 0)");
  int code = 0;
  if (const std::optional<int> stop = tsupport::parse_args(app, argc, argv)) {
    code = *stop;
  } else {
    try {
      code = run(o, rank, ranks);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_mpi (rank %d): %s\n", rank, e.what());
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
  }
  MPI_Finalize();
  return code;
}
