#include "knoblab/design/templates.hpp"

#include <cmath>
#include <numbers>

namespace knoblab::design {

namespace {

constexpr double kPi = std::numbers::pi;

// Points of f at n + 1 evenly spaced x on [a, b].
template <class F>
Waveform sampled(double a, double b, int n, F f) {
  Waveform w;
  for (int i = 0; i <= n; ++i) {
    const double x = a + (b - a) * i / n;
    w.points.push_back({x, f(x)});
  }
  return w;
}

}  // namespace

Tile detent_series() {
  constexpr int kPerRev = 12;
  constexpr double kAmplitude = 0.010;  // N·m
  // Eight points a detent draw its sine closely enough to feel as one.
  // The knob resists with τ, so a detent rests where τ rises through 0.
  return {"detent series", sampled(0.0, 2.0 * kPi, 8 * kPerRev, [](double th) { return kAmplitude * std::sin(kPerRev * th); }),
          Channel::Position};
}

Tile ramp() {
  return {"ramp", sampled(0.0, 0.5, 4, [](double th) { return 0.050 * th / 0.5; }), Channel::Position};
}

Tile wall_clockwise() {
  // Stiff for its first 0.15 rad, then level, so a hand pushing on is held
  // rather than let through where the tile ends. The level is drawn with a
  // point every 0.05 rad past the knee: a cubic spline through a knee rings
  // over the intervals after it, and through 0.15, 0.30, 0.60 alone it
  // swung from 136 to 107 mN·m, more than a detent; now 123 to 119.
  Waveform w;
  w.points = {{0.0, 0.0},    {0.05, 0.040}, {0.10, 0.080}, {0.15, 0.120}, {0.20, 0.120},
              {0.25, 0.120}, {0.30, 0.120}, {0.45, 0.120}, {0.60, 0.120}};
  return {"wall, clockwise end", w, Channel::Position};
}

Tile wall_anticlockwise() {
  Tile t = wall_clockwise();
  t.name = "wall, anticlockwise end";
  Waveform mirrored;
  for (auto it = t.waveform.points.rbegin(); it != t.waveform.points.rend(); ++it)
    mirrored.points.push_back({-it->x, -it->y});
  t.waveform = mirrored;
  return t;
}

Tile constant_damping() {
  constexpr double kB = 0.0005;  // N·m·s/rad
  return {"constant damping", sampled(-20.0, 20.0, 2, [](double v) { return kB * v; }), Channel::Velocity};
}

Tile stribeck_curve() {
  // τ(v) = sign(v)·(Fc + (Fs − Fc)·exp(−(v/vs)²)) + B·v, with the sign
  // smoothed over ±v0 so the curve is a function a spline can follow.
  constexpr double Fc = 0.003, Fs = 0.005, vs = 1.0, B = 0.0002, v0 = 0.2;
  const double vs_at[] = {-20, -10, -5, -3, -2, -1.5, -1, -0.6, -0.3, -0.1, 0, 0.1, 0.3, 0.6, 1, 1.5, 2, 3, 5, 10, 20};
  Waveform w;
  for (const double v : vs_at)
    w.points.push_back({v, std::tanh(v / v0) * (Fc + (Fs - Fc) * std::exp(-(v / vs) * (v / vs))) + B * v});
  return {"Stribeck curve", w, Channel::Velocity};
}

Tile constant_mass() {
  constexpr double kM = 0.0001;  // kg·m²
  Waveform w;
  w.points = {{0.0, kM}, {1.0, kM}};
  return {"constant mass", w, Channel::Acceleration};
}

PaletteTab template_tab() {
  return {kTemplatesTab,
          {detent_series(), ramp(), wall_clockwise(), wall_anticlockwise(), constant_damping(), stribeck_curve(),
           constant_mass()}};
}

Design new_design(const std::string& name) {
  Design d;
  d.name = name;
  d.palette.push_back(template_tab());
  return d;
}

}  // namespace knoblab::design
