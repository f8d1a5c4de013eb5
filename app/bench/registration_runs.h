// The measurements behind `ipd bench registration`: one row per method configuration run over a tier's cases,
// the floor and ceiling rows no method can beat, the pycpd port, and the extra runs (failures, time against the
// rock count, the work bound, the F1-against-time plot).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/bench/registration_benchmark.h"
#include "core/registration/registration.h"

namespace ipd::cli {

// One method with one search budget.
struct MethodConfig {
  RegistrationMethod method;
  int budget;  // paper: K; consensus: hypothesis cap; cpd: EM iterations
};

// One line of the benchmark table: a method configuration (or a bound) over a tier's cases.
struct BenchRow {
  std::string regime, method;  // method: a registration method's name, "pycpd-numpy", "floor" or "ceiling"
  MethodConfig config;
  int cases = 0;
  double ms_per_pair = 0, ms_median = 0, f1 = 0, precision = 0, recall = 0, terr_median = 0, terr_p90 = 0;
  double ambiguous = -1, f1_ambiguous = 0;  // fraction of cases flagged, and their mean F1 (-1: not reported)
};

// Runs one configuration over the cases, one after another on this thread.
BenchRow run_config(const std::vector<RegistrationCase>& cases, const std::string& regime, const MethodConfig& c,
                    double aspect);

// The default method's cases below F1 1, one line each: what the case holds and what went wrong.
void list_failures(const std::vector<RegistrationCase>& cases, const std::string& regime, double aspect);

// What no method can beat on these cases: the transform error of least squares on the true pairs (the
// floor) and the pair F1 of the true affine with our pairing (the ceiling).
std::vector<BenchRow> bounds_rows(const std::vector<RegistrationCase>& cases, const std::string& regime, double aspect);

// The Python baseline (app/bench/pycpd_reference.py) on the same cases, scored exactly like ours.
BenchRow run_pycpd(const std::vector<RegistrationCase>& cases, const std::string& regime, const std::string& script,
                   double aspect);

// The speed goal in the fold run: the default method against the pycpd port on every fold's validation cases.
void compare_with_pycpd(const std::vector<LabelPair>& pairs, const std::vector<MisalignmentRange>& tiers, int cases,
                        std::uint64_t seed, const std::string& script, double W, double H);

// Time of the default method against the rock count (the goal: no worse than n log n up to 500 a side).
void print_scaling(double aspect, std::uint64_t seed);

// Every method on 5,000 rocks a side with its default settings, ended by the work budget.
void print_work_bound(std::uint64_t seed);

// Pair F1 against ms per image pair (log), one panel per tier, to a PNG.
void plot_f1_against_time(const std::vector<BenchRow>& rows, const std::string& path);

}  // namespace ipd::cli
