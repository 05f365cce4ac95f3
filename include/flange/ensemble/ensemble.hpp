// Ensembles: many simulations of one scene type at run-time parameters.
//
//   auto cases = ensemble::grid<2>({"kp", "m_load"}, {ensemble::linspace(2, 40, 20), ensemble::linspace(0.1, 2, 20)});
//   auto study = ensemble::make(
//       [](const std::array<double, 2>& c) { return std::pair{make_crane(c[0], c[1]), Crane::state_type{…}}; },
//       0.0, 10.0, {.tolerance = 1e-8},      // t0, t1 and simulate's options (simulate/options.hpp)
//       ensemble::maximum("max_swing", swing), ensemble::settling_time("settle", error, 1.0));
//   auto res = study.run(cases);                          // serial
//   auto res = study.run(cases, ensemble::tbb_threads{}); // all cores (flange/ensemble/tbb.hpp)
//   res.write_csv(std::cout, cases);
//
// setup(case) builds the scene and its initial state from the case's
// parameters: only run-time values change, the scene type is compiled once.
// Each case is integrated as simulate(scene, x0, t0, t1, options) integrates
// it (the same loop, the same checks and projections, its own evaluation
// budget), with a dense-output method (dopri5 by default); the recorders
// watch every accepted step. So a case's results are bit for bit those of
// simulate(), and they do not depend on how many threads or ranks run the
// ensemble.
//
// Nothing is lost: a case that throws (bad parameters in setup, a
// simulation_error: a non-finite state, a singular mass matrix, a spent
// budget, a step size that collapsed) is recorded with its reason, the time
// and the last accepted state, and the other cases go on.
//
// Cases run in blocks (default 1024): each block is computed (in parallel,
// with a parallel policy), then handed in case order to a sink. run() keeps
// every row; stream() hands each block to a sink of yours (write_csv_rows to
// an open file), so a sweep of 10⁷ cases never holds more than one block.
//
// No heap allocation per case in the stepping loop: the scene, the state and
// the stepper's buffers live on the worker's stack, the recorders are copied
// (they hold string literals, not strings), and a row's reason string stays
// empty unless the case fails.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <unistd.h>

#include "flange/ensemble/cases.hpp"
#include "flange/ensemble/record.hpp"
#include "flange/simulate/simulate.hpp"

namespace flange::ensemble {

/// The methods an ensemble integrates with: flange::method (method.hpp),
/// dopri5 by default.
namespace method = ::flange::method;

/// The integration loop's watcher in an ensemble case: hands the recorders
/// the start and each step, and keeps the last accepted state (a failed
/// case's fail_state).
template <class S, class X, class Recs>
struct record_steps {
  const S& scene;
  Recs& recs;
  X& last;
  bool& have_last;
  void start(const X& x0, double t) {
    std::apply([&](auto&... r) { (r.start(scene, t, x0), ...); }, recs);
    last = x0;
    have_last = true;
  }
  template <class View>
  void step(const View& v) {
    std::apply([&](auto&... r) { (r.step(v), ...); }, recs);
    last = v.x1;
  }
};

/// The span and options of the earlier make(setup, integration, …); use
/// make(setup, t0, t1, simulate_options, …), which takes simulate's options.
struct integration {
  double t0 = 0.0, t1 = 1.0;
  double dt = 1e-3;
  double abs_tol = 1e-8, rel_tol = 1e-8;
  long max_rhs_evals = 10'000'000;
  [[nodiscard]] simulate_options options() const {
    return {.tolerance = abs_tol, .dt = dt, .max_rhs_evals = max_rhs_evals, .rel_tolerance = rel_tol};
  }
};

/// One case's row: its values (NaN where a recorder saw nothing, or the case
/// failed) and what it cost; for a failed case, why, when and where.
template <int NOut, int NState>
struct outcome {
  std::size_t index = 0;
  bool ok = false;
  std::array<double, NOut> values{};
  long rhs_evals = 0, steps = 0;
  double fail_time = std::numeric_limits<double>::quiet_NaN();
  std::array<double, NState> fail_state{};  ///< the last accepted state before the failure (NaN if none)
  std::string reason;                       ///< empty when ok
};

/// Every case's row, in case order.
template <int NOut, int NState>
struct results {
  std::array<std::string, NOut> outputs;
  std::vector<outcome<NOut, NState>> rows;

  [[nodiscard]] std::size_t failed() const {
    return static_cast<std::size_t>(std::count_if(rows.begin(), rows.end(), [](const auto& r) { return !r.ok; }));
  }
  /// The CSV header and every row (write_csv_header, write_csv_rows).
  template <int K>
  void write_csv(std::ostream& os, const case_set<K>& cases) const;
};

/// CSV: case, the parameters, ok, the outputs, evaluations, steps, and for
/// failed cases the time and the reason (quoted). pandas.read_csv and
/// gnuplot (set datafile separator ",") read it as it is.
template <int K, class Names>
void write_csv_header(std::ostream& os, const case_set<K>& cases, const Names& outputs) {
  os << "case";
  for (const auto& n : cases.names) os << ',' << n;
  os << ",ok";
  for (const auto& n : outputs) os << ',' << n;
  os << ",rhs_evals,steps,fail_time,reason\n";
}
template <int K, class It>
void write_csv_rows(std::ostream& os, const case_set<K>& cases, It first, It last) {
  const auto old = os.precision(17);
  for (auto it = first; it != last; ++it) {
    const auto& r = *it;
    os << r.index;
    for (double p : cases[r.index]) os << ',' << p;
    os << ',' << (r.ok ? 1 : 0);
    for (double v : r.values) os << ',' << v;
    os << ',' << r.rhs_evals << ',' << r.steps << ',';
    if (!r.ok) {
      os << r.fail_time << ",\"";
      for (char ch : r.reason) os << (ch == '"' ? '\'' : ch == '\n' ? ' ' : ch);
      os << '"';
    } else {
      os << ',';
    }
    os << '\n';
  }
  os.precision(old);
}
template <int NOut, int NState>
template <int K>
void results<NOut, NState>::write_csv(std::ostream& os, const case_set<K>& cases) const {
  write_csv_header(os, cases, outputs);
  write_csv_rows(os, cases, rows.begin(), rows.end());
}

/// Runs cases one after another on the calling thread.
struct serial {
  template <class F>
  void for_each(std::size_t n, F&& f) const {
    for (std::size_t i = 0; i < n; ++i) f(i);
  }
};

/// The progress line: "cases done/total, rate, time left", on stderr, at most
/// twice a second, only when stderr is a terminal (or when forced).
class progress {
 public:
  progress(std::size_t total, bool enabled) : total_(total), on_(enabled), start_(clock::now()) {}
  void tick() {
    const std::size_t d = done_.fetch_add(1, std::memory_order_relaxed) + 1;
    if (!on_) return;
    const double now = seconds();
    double next = next_.load(std::memory_order_relaxed);
    if (now < next || !next_.compare_exchange_strong(next, now + 0.5)) return;
    const double rate = d / std::max(now, 1e-9);
    std::fprintf(stderr, "\rcases %zu/%zu, %.3g/s, %.1f s left   ", d, total_, rate,
                 static_cast<double>(total_ - d) / std::max(rate, 1e-9));
    std::fflush(stderr);
  }
  void finish() const {
    if (on_) std::fprintf(stderr, "\rcases %zu/%zu in %.2f s%20s\n", done_.load(), total_, seconds(), "");
  }
  static bool terminal() { return isatty(STDERR_FILENO) == 1; }

 private:
  using clock = std::chrono::steady_clock;
  double seconds() const { return std::chrono::duration<double>(clock::now() - start_).count(); }
  std::size_t total_;
  bool on_;
  clock::time_point start_;
  std::atomic<std::size_t> done_{0};
  std::atomic<double> next_{0.0};
};

/// Options of a run: the block size (rows held at once) and the progress line.
struct run_options {
  std::size_t block = 1024;
  enum class show { if_terminal, always, never } progress_line = show::if_terminal;
};

/// Tells a recorder which case it records, if it asks (a recorder that
/// writes into an array of the caller's, row by case: states_at).
template <class R>
void begin_case(R& r, std::size_t index) {
  if constexpr (requires { r.begin_case(index); }) r.begin_case(index);
}

/// An ensemble: how to build a case's scene, how to integrate it, what to record.
template <class Setup, class Method, class... Recorders>
class study {
  template <int K>
  using scene_and_state = std::invoke_result_t<const Setup&, const std::array<double, K>&>;

 public:
  /// Each case from t0 to t1 with simulate's options (simulate/options.hpp).
  study(Setup setup, double t0, double t1, const simulate_options& o, Recorders... recs)
      : setup_(std::move(setup)), t0_(t0), t1_(t1), options_(o), recs_(recs...) {
    ::flange::detail::check_run("ensemble", o, t0, t1);
    if (!(t1 > t0))
      throw parameter_error(::flange::detail::concat("flange: ensemble: needs t1 > t0 (got t0 = ", t0, ", t1 = ", t1,
                                                     ")"));
  }

  template <int K>
  using scene_type = std::remove_cvref_t<decltype(std::get<0>(std::declval<scene_and_state<K>>()))>;
  template <int K>
  using state_type = std::remove_cvref_t<decltype(std::get<1>(std::declval<scene_and_state<K>>()))>;
  template <int K>
  static constexpr int n_outputs = (0 + ... + Recorders::template width<scene_type<K>>());
  template <int K>
  using outcome_type = outcome<n_outputs<K>, scene_type<K>::n_state>;
  template <int K>
  using results_type = results<n_outputs<K>, scene_type<K>::n_state>;

  /// The output column names.
  template <int K>
  std::array<std::string, n_outputs<K>> outputs() const {
    std::array<std::string, n_outputs<K>> names;
    int at = 0;
    std::apply([&](const auto&... r) { ((r.template names<scene_type<K>>(names.data() + at),
                                         at += std::remove_cvref_t<decltype(r)>::template width<scene_type<K>>()),
                                        ...); },
               recs_);
    return names;
  }

  /// One case, as every policy runs it: the loop simulate() runs, with the
  /// same checks, so a case ends bit for bit where simulate<Method> ends and
  /// is projected where the scene needs it; the recorders watch the start
  /// and each step.
  template <int K>
  outcome_type<K> run_case(const case_set<K>& cases, std::size_t index) const {
    using S = scene_type<K>;
    using X = state_type<K>;
    outcome_type<K> o;
    o.index = index;
    o.values.fill(not_seen);
    o.fail_state.fill(not_seen);
    X last{};
    bool have_last = false;
    long evals = 0;
    try {
      auto made = setup_(cases[index]);
      const S& s = std::get<0>(made);
      X& x = std::get<1>(made);
      auto recs = recs_;  // this case's recorders
      std::apply([&](auto&... r) { (begin_case(r, index), ...); }, recs);
      record_steps<S, X, decltype(recs)> watch{s, recs, last, have_last};
      o.steps = ::flange::detail::checked_run<Method>(s, x, t0_, t1_, options_, evals, watch);
      int at = 0;
      std::apply([&](auto&... r) {
        ((r.finish(s, t1_, x, o.values.data() + at), at += std::remove_cvref_t<decltype(r)>::template width<S>()),
         ...);
      }, recs);
      o.ok = true;
    } catch (const simulation_error& e) {
      o.reason = e.what();
      o.fail_time = e.time;
      o.values.fill(not_seen);
      o.steps = 0;
    } catch (const std::exception& e) {
      o.reason = e.what();
      o.values.fill(not_seen);
      o.steps = 0;
    }
    if (!o.ok && have_last)
      for (int i = 0; i < S::n_state; ++i) o.fail_state[i] = static_cast<double>(last[i]);
    o.rhs_evals = evals;
    return o;
  }

  /// Runs the cases first, first + stride, … (all of them by default) with
  /// a policy, and hands every block's rows, in case order, to sink(first, last).
  template <int K, class Policy, class Sink>
  void stream(const case_set<K>& cases, const Policy& policy, Sink&& sink, run_options opt = {},
              std::size_t first = 0, std::size_t stride = 1) const {
    const std::size_t n = first < cases.size() ? (cases.size() - first + stride - 1) / stride : 0;
    const std::size_t block = std::max<std::size_t>(opt.block, 1);
    progress bar(n, opt.progress_line == run_options::show::always ||
                        (opt.progress_line == run_options::show::if_terminal && progress::terminal()));
    std::vector<outcome_type<K>> rows(std::min(block, n));
    for (std::size_t b0 = 0; b0 < n; b0 += block) {
      const std::size_t m = std::min(block, n - b0);
      policy.for_each(m, [&](std::size_t j) {
        rows[j] = run_case(cases, first + (b0 + j) * stride);
        bar.tick();
      });
      sink(rows.cbegin(), rows.cbegin() + static_cast<std::ptrdiff_t>(m));
    }
    bar.finish();
  }

  /// Every case's row, in case order.
  template <int K, class Policy = serial>
  results_type<K> run(const case_set<K>& cases, const Policy& policy = {}, run_options opt = {}) const {
    results_type<K> r{outputs<K>(), {}};
    r.rows.reserve(cases.size());
    stream(cases, policy, [&](auto b, auto e) { r.rows.insert(r.rows.end(), b, e); }, opt);
    return r;
  }

  [[nodiscard]] double t0() const { return t0_; }
  [[nodiscard]] double t1() const { return t1_; }
  [[nodiscard]] const simulate_options& options() const { return options_; }

 private:
  Setup setup_;
  double t0_, t1_;
  simulate_options options_;
  std::tuple<Recorders...> recs_;
};

/// An ensemble whose cases run from t0 to t1 as simulate() runs them, with
/// its options, integrated with dopri5 (dense output).
template <class Setup, class... Recorders>
study<Setup, method::dopri5, Recorders...> make(Setup setup, double t0, double t1, const simulate_options& o,
                                                Recorders... recs) {
  return {std::move(setup), t0, t1, o, recs...};
}
/// The same with another dense-output method (see ensemble::method).
template <class Method, class Setup, class... Recorders>
study<Setup, Method, Recorders...> make_with(Setup setup, double t0, double t1, const simulate_options& o,
                                             Recorders... recs) {
  return {std::move(setup), t0, t1, o, recs...};
}
template <class Setup, class... Recorders>
[[deprecated("flange: write ensemble::make(setup, t0, t1, {.tolerance = …, .dt = …, .max_rhs_evals = …}, "
             "recorders…): an ensemble takes simulate's options")]]
study<Setup, method::dopri5, Recorders...> make(Setup setup, integration in, Recorders... recs) {
  return {std::move(setup), in.t0, in.t1, in.options(), recs...};
}
template <class Method, class Setup, class... Recorders>
[[deprecated("flange: write ensemble::make_with<Method>(setup, t0, t1, {.tolerance = …}, recorders…): an "
             "ensemble takes simulate's options")]]
study<Setup, Method, Recorders...> make_with(Setup setup, integration in, Recorders... recs) {
  return {std::move(setup), in.t0, in.t1, in.options(), recs...};
}

}  // namespace flange::ensemble
