// Reading and comparing the free-body trajectories that
// contact_reference.cpp writes (Simbody's), for contact_test.cpp and
// contact_shapes_test.cpp: rows "t x y z Qx Qy Qz Qw vx vy vz wx wy wz",
// one block of contact_scenes::samples + 1 rows per scene.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <flange/flange.hpp>

#include "contact_scenes.hpp"

namespace contact_scenes {

using row = std::array<double, 14>;

/// Block `block` (0: the ball, 1: the box) of the file; empty if it is short.
inline std::vector<row> read_block(const std::string& path, int block) {
  std::ifstream in(path);
  std::vector<row> rows;
  for (row r; in >> r[0];) {
    for (int i = 1; i < 14; ++i) in >> r[i];
    rows.push_back(r);
  }
  const std::size_t n = samples + 1;
  if (rows.size() < (block + 1) * n) return {};
  return {rows.begin() + block * n, rows.begin() + (block + 1) * n};
}

/// How a flange run compares with Simbody's rows: the largest difference in
/// any state entry (a quaternion and its negative being one rotation), the
/// largest scaled residual on the recovered variables, the lowest centre.
struct comparison {
  double worst = 0, worst_residual = 0, lowest = 1;
};

/// Simulates scene s from x0 at the rows' times (at 1e-12, as Simbody ran)
/// and compares; `end` receives the last state.
template <class S>
comparison compare(const S& s, const typename S::state_type& x0, const std::vector<row>& rows,
                   typename S::state_type& end) {
  std::vector<double> times;
  for (const auto& r : rows) times.push_back(r[0]);
  const auto tr = flange::simulate(s, x0, times, {.tolerance = 1e-12});
  comparison c;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double sign = tr.x[k][6] * rows[k][7] < 0 ? -1 : 1;
    for (int i = 0; i < 13; ++i)
      c.worst = std::max(c.worst, std::abs(tr.x[k][i] - (i >= 3 && i < 7 ? sign : 1) * rows[k][i + 1]));
    c.worst_residual = std::max(c.worst_residual, flange::scaled_residual(s, flange::recover(s, tr.t[k], tr.x[k])));
    c.lowest = std::min(c.lowest, tr.x[k][1]);
  }
  end = tr.x.back();
  return c;
}

}  // namespace contact_scenes
