// Bracketed scalar root finders (core/illinois.hpp): both converge to the root to the requested
// tolerance on smooth and on badly scaled functions, keep it bracketed, and the secant variant
// needs fewer evaluations where the function is smooth (the reason the geomodel uses it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/illinois.hpp"

namespace ballista::test_root_finding {
namespace {

struct Counted {
  double (*f)(double);
  int calls = 0;
  double operator()(double x) {
    ++calls;
    return f(x);
  }
};

double cubic(double x) { return x * x * x - 2.0 * x - 5.0; }  // Newton's own example: root 2.0945514815423265
double expo(double x) { return std::exp(x) - 10.0; }         // root ln 10
double steep(double x) { return std::atan(1e6 * (x - 0.3)); }  // a near step at 0.3
double flat(double x) { return std::pow(x - 0.7, 3); }         // triple root: linear convergence only

TEST(RootFinding, SecantAndIllinoisFindTheRoot) {
  struct Case {
    double (*f)(double);
    double a, b, root;
  };
  const Case cases[] = {{cubic, 1.0, 3.0, 2.0945514815423265},
                        {expo, 0.0, 5.0, std::log(10.0)},
                        {steep, 0.0, 1.0, 0.3},
                        {flat, 0.0, 1.0, 0.7}};
  for (const Case& c : cases) {
    Counted fs{c.f}, fi{c.f};
    // Tolerances: 1e-12 in x; the triple root's |f| <= 1e-30 also means |x - 0.7| <= 1e-10.
    const double xs = bracketed_secant_root(fs, c.a, c.f(c.a), c.b, c.f(c.b), 1e-12, 1e-30, 200);
    const double xi = illinois_root(fi, c.a, c.f(c.a), c.b, c.f(c.b), 1e-12, 1e-30, 200);
    const double tol = c.f == flat ? 1e-9 : 1e-11;
    EXPECT_NEAR(xs, c.root, tol) << "secant, case with root " << c.root << ", " << fs.calls << " calls";
    EXPECT_NEAR(xi, c.root, tol) << "Illinois, case with root " << c.root << ", " << fi.calls << " calls";
    EXPECT_LT(fs.calls, 200);
  }
}

// On smooth functions the secant through the latest points (order 1.618) needs no more
// evaluations than Illinois (order ~1.44), and strictly fewer on at least one of them. Stopped at
// |f| <= 1e-9, well above the round-off floor (at the floor |f| is noise, neither method
// progresses, and the counts depend on the compiler's floating-point contractions).
TEST(RootFinding, SecantIsNoSlowerOnSmoothFunctions) {
  int fewer = 0;
  for (auto f : {cubic, expo}) {
    Counted fs{f}, fi{f};
    bracketed_secant_root(fs, 1.0, f(1.0), 3.0, f(3.0), 0.0, 1e-9, 200);
    illinois_root(fi, 1.0, f(1.0), 3.0, f(3.0), 0.0, 1e-9, 200);
    std::printf("secant %d, Illinois %d evaluations\n", fs.calls, fi.calls);
    EXPECT_LE(fs.calls, fi.calls);
    fewer += fs.calls < fi.calls;
  }
  EXPECT_GE(fewer, 1);
}

}  // namespace
}  // namespace ballista::test_root_finding
