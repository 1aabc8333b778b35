#pragma once
// Angle arithmetic for joint controllers (radians). Real-time safe: no
// allocation, no exceptions.
namespace servoloop::controllers {

// x wrapped into (-π, π]. Non-finite input is returned unchanged.
double wrapToPi(double angle_rad) noexcept;

// The signed angle that turns from_rad into to_rad the short way round, in
// [-π, π] (continuous joints).
double shortestAngularDistance(double from_rad, double to_rad) noexcept;

// The displacement d with from_rad + d ≡ to_rad (mod 2π) and the smallest |d|
// among those whose end point from_rad + d lies inside [lower_rad, upper_rad]
// (revolute joints: the joint reaches the target without passing a limit).
// When no end point lies inside the limits (to_rad is outside them and the
// range is narrower than 2π), returns to_rad - from_rad.
double shortestAngularDistanceWithinLimits(double from_rad, double to_rad, double lower_rad,
                                           double upper_rad) noexcept;

}  // namespace servoloop::controllers
