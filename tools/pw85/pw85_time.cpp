// Times pw85's contact function (S. Brisard, https://github.com/sbrisard/pw85, v2,
// header-only C++ with Boost) on one of grainpack's reference sets, the way
// `pack contact SET --time` times ours: whole passes over the set until at least
// MIN_ROUNDS passes and MIN_SECONDS have elapsed, the median pass's mean time per
// call. Also prints the largest relative error of its mu^2 against the set's mpmath
// reference. Built and run by tools/pw85/run.sh; pw85 itself is not part of grainpack.
#include <pw85/pw85.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

// The same as grainpack's `Method::time` is called with by `pack contact --time`.
constexpr size_t MIN_ROUNDS = 5;
constexpr double MIN_SECONDS = 0.2;

struct Pair {
  double r[3], q1[6], q2[6], mu2;
};

int main(int argc, char **argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: pw85_time SET.csv\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in) {
    std::fprintf(stderr, "pw85_time: cannot read %s\n", argv[1]);
    return 1;
  }
  std::vector<Pair> pairs;
  std::string line;
  std::getline(in, line);  // header: r0..r2, q1_0..q1_5, q2_0..q2_5, mu2, lambda[, category]
  for (size_t row = 2; std::getline(in, line); row++) {
    std::stringstream cells(line);
    std::string cell;
    double v[16];
    for (double &x : v) {
      if (!std::getline(cells, cell, ',')) {
        std::fprintf(stderr, "pw85_time: %s line %zu: fewer than 16 columns\n", argv[1], row);
        return 1;
      }
      x = std::stod(cell);
    }
    Pair p;
    std::copy(v, v + 3, p.r);
    std::copy(v + 3, v + 9, p.q1);
    std::copy(v + 9, v + 15, p.q2);
    p.mu2 = v[15];
    pairs.push_back(p);
  }
  if (pairs.empty()) {
    std::fprintf(stderr, "pw85_time: %s has no pairs\n", argv[1]);
    return 1;
  }

  double max_rel = 0.0, out[2];
  for (const Pair &p : pairs) {
    pw85::contact_function(p.r, p.q1, p.q2, out);
    max_rel = std::max(max_rel, std::fabs(out[0] - p.mu2) / p.mu2);
  }

  using clock = std::chrono::steady_clock;
  std::vector<double> per_call;
  volatile double sink = 0.0;
  auto start = clock::now();
  while (per_call.size() < MIN_ROUNDS ||
         std::chrono::duration<double>(clock::now() - start).count() < MIN_SECONDS) {
    auto t = clock::now();
    double sum = 0.0;
    for (const Pair &p : pairs) {
      pw85::contact_function(p.r, p.q1, p.q2, out);
      sum += out[0];
    }
    sink = sink + sum;
    per_call.push_back(std::chrono::duration<double, std::nano>(clock::now() - t).count() /
                       pairs.size());
  }
  std::sort(per_call.begin(), per_call.end());
  std::printf("{\"method\":\"pw85\",\"pairs\":%zu,\"rounds\":%zu,\"ns_per_call_median\":%.1f,"
              "\"ns_per_call_min\":%.1f,\"max_rel_error\":%.2e}\n",
              pairs.size(), per_call.size(), per_call[per_call.size() / 2], per_call[0], max_rel);
  return 0;
}
