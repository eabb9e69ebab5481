// `anneal`: simulated annealing (Kirkpatrick, Gelatt, Vecchi, "Optimization by Simulated Annealing", Science 220,
// 1983) over a Problem's box, moving on the storage lattice for parameters that have one (the annealing searches of
// "HDR Texture Compression for Graphics Hardware", 2006, and its 2008 sequel search the quantised endpoints;
// DESIGN.md lists annealing among the per-block solvers).
//
// One run: from the run's start point, `iterations` moves; each move changes ONE parameter, chosen uniformly among
// the movable ones (a lattice with count > 1, or a continuous parameter with upper > lower):
//   * continuous parameter p: x_p + N(0, 1) * step_size * (upper_p - lower_p) * sqrt(T_k / T_0), reflected at the
//     bounds (then clamped, for steps longer than the box);
//   * lattice parameter p: index +- m lattice steps, m = 1 + floor(|N(0, 1)| * step_size * (count_p - 1) *
//     sqrt(T_k / T_0)) (never a zero move), reflected at the ends of the lattice.
// The step shrinks with sqrt(T_k / T_0), tying the generating width to the temperature as fast annealing does
// (Szu & Hartley 1987; Ingber 1989), so the cold end of a run is a local descent.
// A move from error E to E' is accepted when E' <= E, or with probability exp(-(E' - E) / T_k) (Metropolis);
// a NaN error is an invalid point and never accepted; a NaN current error accepts any valid candidate.
//
// Temperatures (t = k / (iterations - 1), T_end = final_temperature_ratio * T_0):
//   geometric    T_k = T_0 * ratio^t                           (constant factor per move)
//   linear       T_k = T_0 * (1 - t (1 - ratio))               (straight line from T_0 to T_end)
//   exponential  T_k = T_0 * exp(-c k^(1/D)), D = number of movable parameters, c such that T_{n-1} = T_end
//                (Ingber's very fast simulated re-annealing schedule; equal to geometric when D = 1)
// T_0 = initial_temperature when temperature_scale = absolute, and initial_temperature * |E(run start)| when
// relative (the default; a start error of 0, infinity or NaN uses |E| = 1), so one setting suits blocks whose
// errors differ by orders of magnitude. Each restart is a new run of `iterations` moves with T_0 recomputed from
// its start point, which is the best point so far (restart_from = best: re-annealing) or a uniformly random point
// of the box / lattice (restart_from = random). The first run starts at `start` (clamped into the box and moved to
// the nearest lattice point) or, without one, at the centre of the box (nearest lattice point).
//
// The answer is the best point ever evaluated (ties keep the earlier one). Randomness: only the `seed` argument,
// through solvers/seeding.h (SplitMix64, portable uniform and normal draws): the same seed gives the same answer on
// any machine with the same libm, whatever the thread count. Termination is max_iterations (the budget was spent)
// or failed (every evaluated point had a NaN error). Continuous parameters need finite bounds (Error otherwise).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solvers/solver.h"

namespace blocklab {

enum class CoolingSchedule { geometric, linear, exponential };
enum class TemperatureScale { relative, absolute };
enum class RestartPoint { best, random };

std::string to_string(CoolingSchedule schedule);
std::string to_string(TemperatureScale scale);
std::string to_string(RestartPoint point);
// Inverses of to_string; throw Error("anneal: unknown cooling schedule 'x'; valid: geometric, linear, exponential").
CoolingSchedule cooling_schedule_from_string(const std::string& name);
TemperatureScale temperature_scale_from_string(const std::string& name);
RestartPoint restart_point_from_string(const std::string& name);

struct AnnealOptions {
  std::int64_t iterations = 2000;              // moves per run; option `iterations`
  std::int64_t restarts = 3;                   // runs after the first (0: one run); option `restarts`
  double initial_temperature = 0.1;            // T_0, relative or absolute; option `initial_temperature`
  TemperatureScale temperature_scale = TemperatureScale::relative;   // option `temperature_scale`
  double final_temperature_ratio = 1e-3;       // T_end / T_0 in (0, 1]; option `final_temperature_ratio`
  CoolingSchedule cooling = CoolingSchedule::geometric;              // option `cooling`
  double step_size = 0.1;                      // initial step, fraction of the box width / lattice; `step_size`
  RestartPoint restart_from = RestartPoint::best;                    // option `restart_from`
  double time_limit = kDefaultTimeLimit;       // wall-time seconds per solve; option `time_limit`

  bool is_valid(std::string* why) const;
  static AnnealOptions from_resolved(const SolverOptions& resolved);
};

// Temperature of move k of a run of `iterations` moves over `movable_count` movable parameters (exposed for tests).
double anneal_temperature(const AnnealOptions& options, double initial_temperature, std::int64_t k,
                          int movable_count);

SolveResult solve_anneal(const Problem& problem, const AnnealOptions& options, const double* start,
                         std::uint64_t seed);

const Solver& anneal_solver();

}  // namespace blocklab
