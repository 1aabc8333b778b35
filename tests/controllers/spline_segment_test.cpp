// The trajectory segments against the polynomials they must reproduce: a
// segment built from the boundary values of a known polynomial of its degree
// is that polynomial (the boundary problem has one solution), so its
// position, velocity and acceleration must match the polynomial's, computed
// here independently, at the knots and everywhere between.
#include <array>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "servoloop/controllers/common/spline_segment.hpp"

namespace servoloop::controllers {
namespace {

// p(t) = sum k[i] (t - t0)^i and its derivatives, by the power rule.
struct Polynomial {
  std::array<double, 6> k{};
  double t0 = 0.0;
  JointSample at(double time) const {
    const double t = time - t0;
    JointSample s;
    for (int i = 0; i < 6; ++i) {
      s.position += k[i] * std::pow(t, i);
      if (i >= 1) s.velocity += i * k[i] * std::pow(t, i - 1);
      if (i >= 2) s.acceleration += i * (i - 1) * k[i] * std::pow(t, i - 2);
    }
    return s;
  }
};

void expectSame(const JointSample& got, const JointSample& want, const std::string& where) {
  const double tolerance = 1e-9;
  EXPECT_NEAR(got.position, want.position, tolerance * (1.0 + std::abs(want.position))) << where;
  EXPECT_NEAR(got.velocity, want.velocity, tolerance * (1.0 + std::abs(want.velocity))) << where;
  EXPECT_NEAR(got.acceleration, want.acceleration, 1e-8 * (1.0 + std::abs(want.acceleration))) << where;
}

// Random polynomials of each degree on random intervals; the segment of the
// matching kind reproduces each at 50 points across the segment.
void checkReproduces(SplineKind kind, int degree) {
  std::mt19937 random(17 + degree);
  std::uniform_real_distribution<double> coefficient(-2.0, 2.0);
  std::uniform_real_distribution<double> start(-5.0, 5.0);
  std::uniform_real_distribution<double> length(0.05, 3.0);
  for (int trial = 0; trial < 200; ++trial) {
    Polynomial p;
    p.t0 = start(random);
    for (int i = 0; i <= degree; ++i) p.k[i] = coefficient(random);
    const double t1 = p.t0 + length(random);
    const SplineSegment segment(p.t0, p.at(p.t0), t1, p.at(t1), kind);
    for (int n = 0; n <= 49; ++n) {
      const double time = n == 49 ? t1 : p.t0 + (t1 - p.t0) * n / 49.0;
      JointSample want = p.at(time);
      if (kind == SplineKind::linear) want.acceleration = 0.0;
      expectSame(segment.sample(time), want, "degree " + std::to_string(degree) + " trial " +
                                                 std::to_string(trial) + " at t = " + std::to_string(time));
    }
  }
}

TEST(SplineSegment, LinearReproducesALine) { checkReproduces(SplineKind::linear, 1); }
TEST(SplineSegment, CubicReproducesACubic) { checkReproduces(SplineKind::cubic, 3); }
TEST(SplineSegment, QuinticReproducesAQuintic) { checkReproduces(SplineKind::quintic, 5); }

// Arbitrary boundary states: each kind meets what it is given at both ends.
TEST(SplineSegment, EachKindMeetsItsBoundaryConditions) {
  const JointSample start{0.3, -1.2, 4.0};
  const JointSample end{-0.7, 0.5, -2.5};
  const SplineSegment quintic(1.0, start, 1.8, end, SplineKind::quintic);
  expectSame(quintic.sample(1.0), start, "quintic start");
  expectSame(quintic.sample(1.8), end, "quintic end");

  const SplineSegment cubic(1.0, start, 1.8, end, SplineKind::cubic);
  EXPECT_NEAR(cubic.sample(1.0).position, start.position, 1e-12);
  EXPECT_NEAR(cubic.sample(1.0).velocity, start.velocity, 1e-12);
  EXPECT_NEAR(cubic.sample(1.8).position, end.position, 1e-12);
  EXPECT_NEAR(cubic.sample(1.8).velocity, end.velocity, 1e-12);

  const SplineSegment linear(1.0, start, 1.8, end, SplineKind::linear);
  EXPECT_NEAR(linear.sample(1.4).position, -0.2, 1e-12);  // half way
  EXPECT_NEAR(linear.sample(1.4).velocity, -1.0 / 0.8, 1e-12);
  EXPECT_EQ(linear.sample(1.4).acceleration, 0.0);
}

// Hand values: a quintic from rest to rest over 2 s from 0 to 1 is
// 10 s^3 - 15 s^4 + 6 s^5 with s = t / 2 (the minimum-jerk profile).
TEST(SplineSegment, RestToRestQuinticIsTheMinimumJerkProfile) {
  const SplineSegment segment(0.0, {0.0, 0.0, 0.0}, 2.0, {1.0, 0.0, 0.0}, SplineKind::quintic);
  for (double t : {0.25, 0.5, 1.0, 1.5, 1.9}) {
    const double s = t / 2.0;
    const double position = 10 * std::pow(s, 3) - 15 * std::pow(s, 4) + 6 * std::pow(s, 5);
    const double velocity = (30 * std::pow(s, 2) - 60 * std::pow(s, 3) + 30 * std::pow(s, 4)) / 2.0;
    const double acceleration = (60 * s - 180 * std::pow(s, 2) + 120 * std::pow(s, 3)) / 4.0;
    expectSame(segment.sample(t), {position, velocity, acceleration}, "t = " + std::to_string(t));
  }
  EXPECT_NEAR(segment.sample(1.0).velocity, 15.0 / 16.0, 1e-12);  // peak speed 1.875 / 2
}

TEST(SplineSegment, OutsideItsTimesItHoldsItsEndsAtRest) {
  const SplineSegment segment(2.0, {0.5, 1.0, 0.0}, 3.0, {1.5, -1.0, 0.0}, SplineKind::cubic);
  const JointSample before = segment.sample(1.0);
  EXPECT_EQ(before.position, 0.5);
  EXPECT_EQ(before.velocity, 0.0);
  EXPECT_EQ(before.acceleration, 0.0);
  const JointSample after = segment.sample(3.5);
  EXPECT_NEAR(after.position, 1.5, 1e-12);
  EXPECT_EQ(after.velocity, 0.0);
  EXPECT_EQ(after.acceleration, 0.0);
}

TEST(SplineSegment, ZeroDurationIsItsEndPoint) {
  const SplineSegment segment(1.0, {0.0, 0.0, 0.0}, 1.0, {2.0, 0.5, 1.0}, SplineKind::quintic);
  expectSame(segment.sample(1.0), {2.0, 0.5, 1.0}, "at the point");
  EXPECT_EQ(segment.sample(0.5).position, 2.0);
  EXPECT_EQ(segment.sample(1.5).position, 2.0);
  const SplineSegment backwards(1.0, {0.0, 0.0, 0.0}, 0.5, {3.0, 0.0, 0.0}, SplineKind::linear);
  EXPECT_EQ(backwards.sample(1.0).position, 3.0);
}

}  // namespace
}  // namespace servoloop::controllers
