// Several simultaneous contacts between planar rigid bodies: an iterative
// impulse solver (sequential impulses, i.e. projected Gauss–Seidel on the
// contact impulses), organised in the three passes of Guendelman, Bridson &
// Fedkiw, "Nonconvex rigid bodies with stacking", ACM TOG 22 (2003) 871–878,
// as summarised in ../shared/seeds/newton-coulomb-impulse-lecture.txt:
//
//   collision pass   up to `collision_iterations` sweeps over the contacts
//                    that approach (u_n < 0), each resolved by the
//                    Newton–Coulomb impulse with e_n; stops when none approach
//   contact pass     after the velocities are advanced by gravity, sweeps
//                    with a restitution ramped from −1 to 0 (the last sweep
//                    is plastic), which puts resting contacts to rest
//   shock propagation bodies taken level by level in the gravity order
//                    (bottom up): the contacts of a level are swept with the
//                    bodies below treated as static, so that the weight of a
//                    stack is carried in one pass instead of one body per
//                    sweep
//
// Each pass reports its sweeps and its residual: the largest approach speed
// max(0, −u_n) over the contacts left at its end (m/s).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "rigidbody/body2d.hpp"
#include "rigidbody/collision_matrix.hpp"
#include "rigidbody/newton_coulomb_impulse.hpp"

namespace impactlab::rigidbody {

// A contact point between bodies a and b; the normal points from b to a.
struct Contact2D {
  int a = 0, b = 0;          // indices into the body list
  Eigen::Vector2d point;     // world contact point (m)
  Eigen::Vector2d normal;    // unit normal, from b towards a
  double depth = 0.0;        // penetration (m), > 0 when overlapping
};

struct PassReport {
  int sweeps = 0;         // full passes over the contact set
  double residual = 0.0;  // max(0, −u_n) over the contacts at the end (m/s)
};

struct SequentialImpulseSettings {
  double e_n = 0.0;               // collision restitution, [0, 1]
  double mu = 0.5;                // Coulomb friction, >= 0
  int collision_iterations = 10;  // N of GBF's collision pass (5–15)
  int contact_iterations = 20;    // sweeps of the contact pass
  int shock_iterations = 20;      // sweeps per level of shock propagation
  double approach_tolerance = 1e-12;  // u_n below −this counts as approaching (m/s)
};

// relative normal velocity of a contact, u_n = n·(u_a − u_b) (m/s)
inline double normal_velocity(const std::vector<Body2D>& bodies, const Contact2D& c) {
  const Body2D& a = bodies[c.a];
  const Body2D& b = bodies[c.b];
  const Eigen::Vector2d u =
      a.point_velocity(c.point - a.position) - b.point_velocity(c.point - b.position);
  return c.normal.dot(u);
}

// Applies the Newton–Coulomb impulse of one contact if it approaches; a body
// flagged in `frozen` is treated as static. Returns the approach speed seen.
inline double resolve_contact(std::vector<Body2D>& bodies, const Contact2D& c, double e_n,
                              double mu, double tolerance, const std::vector<char>* frozen = nullptr) {
  Body2D a = bodies[c.a];
  Body2D b = bodies[c.b];
  if (frozen && (*frozen)[c.a]) a.inverse_mass = a.inverse_inertia = 0.0;
  if (frozen && (*frozen)[c.b]) b.inverse_mass = b.inverse_inertia = 0.0;
  const Eigen::Vector2d r_a = c.point - a.position;
  const Eigen::Vector2d r_b = c.point - b.position;
  const Eigen::Vector2d u = a.point_velocity(r_a) - b.point_velocity(r_b);
  if (!(c.normal.dot(u) < -tolerance)) return 0.0;
  const Eigen::Matrix2d K = collision_matrix(a, r_a, b, r_b);
  const auto impulse = newton_coulomb_impulse<2>(K, u, c.normal, {e_n, mu, 0.0});
  if (impulse.regime == ImpulseRegime::inconsistent) return -c.normal.dot(u);
  a.apply_impulse(impulse.impulse, r_a);
  b.apply_impulse(-impulse.impulse, r_b);
  if (!(frozen && (*frozen)[c.a])) bodies[c.a] = a;
  if (!(frozen && (*frozen)[c.b])) bodies[c.b] = b;
  return -c.normal.dot(u);
}

inline double approach_residual(const std::vector<Body2D>& bodies,
                                const std::vector<Contact2D>& contacts) {
  double worst = 0.0;
  for (const auto& c : contacts) worst = std::max(worst, -normal_velocity(bodies, c));
  return worst;
}

// GBF's collision pass.
inline PassReport collision_pass(std::vector<Body2D>& bodies, const std::vector<Contact2D>& contacts,
                                 const SequentialImpulseSettings& s) {
  PassReport report;
  for (; report.sweeps < s.collision_iterations;) {
    ++report.sweeps;
    bool any = false;
    for (const auto& c : contacts)
      any = resolve_contact(bodies, c, s.e_n, s.mu, s.approach_tolerance) > 0.0 || any;
    if (!any) break;
  }
  report.residual = approach_residual(bodies, contacts);
  return report;
}

// GBF's contact pass: restitution ramped from −1 towards 0, the last sweep plastic.
inline PassReport contact_pass(std::vector<Body2D>& bodies, const std::vector<Contact2D>& contacts,
                               const SequentialImpulseSettings& s) {
  PassReport report;
  const int sweeps = std::max(1, s.contact_iterations);
  for (int k = 0; k < sweeps; ++k) {
    ++report.sweeps;
    const double restitution = sweeps > 1 ? -static_cast<double>(sweeps - 1 - k) / (sweeps - 1) : 0.0;
    for (const auto& c : contacts) resolve_contact(bodies, c, restitution, s.mu, s.approach_tolerance);
  }
  report.residual = approach_residual(bodies, contacts);
  return report;
}

// Shock propagation: levels[k] lists the bodies of level k, bottom up along
// gravity; the bodies of the levels below are static while a level is swept.
inline PassReport shock_propagation(std::vector<Body2D>& bodies,
                                    const std::vector<Contact2D>& contacts,
                                    const std::vector<std::vector<int>>& levels,
                                    const SequentialImpulseSettings& s) {
  PassReport report;
  std::vector<char> frozen(bodies.size(), 0);
  for (std::size_t i = 0; i < bodies.size(); ++i) frozen[i] = bodies[i].is_static() ? 1 : 0;
  std::vector<char> in_level(bodies.size(), 0);
  for (const auto& level : levels) {
    std::fill(in_level.begin(), in_level.end(), 0);
    for (int body : level) in_level[body] = 1;
    for (int sweep = 0; sweep < s.shock_iterations; ++sweep) {
      ++report.sweeps;
      bool any = false;
      for (const auto& c : contacts)
        if (in_level[c.a] || in_level[c.b])
          any = resolve_contact(bodies, c, 0.0, s.mu, s.approach_tolerance, &frozen) > 0.0 || any;
      if (!any) break;
    }
    for (int body : level) frozen[body] = 1;
  }
  report.residual = approach_residual(bodies, contacts);
  return report;
}

// One sweep of GBF's position correction ("first-order physics"): each
// overlapping contact is pushed apart by `fraction` of its depth along the
// normal, shared in proportion to the inverse masses. The caller recomputes
// the contacts between sweeps and raises the fraction to 1 in the last one.
inline void correct_positions(std::vector<Body2D>& bodies, const std::vector<Contact2D>& contacts,
                              double fraction) {
  for (const auto& c : contacts) {
    if (!(c.depth > 0.0)) continue;
    Body2D& a = bodies[c.a];
    Body2D& b = bodies[c.b];
    const double total = a.inverse_mass + b.inverse_mass;
    if (total == 0.0) continue;
    const double push = fraction * c.depth / total;
    a.position += push * a.inverse_mass * c.normal;
    b.position -= push * b.inverse_mass * c.normal;
  }
}

}  // namespace impactlab::rigidbody
