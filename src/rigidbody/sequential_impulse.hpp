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
//                    that put the resting contacts to rest (projected
//                    Gauss–Seidel with a plastic target; GBF ramp a
//                    restitution from −1 to 0 instead, see contact_pass)
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
#include <cstddef>
#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <impactlab/rigidbody/body2d.hpp>
#include <impactlab/rigidbody/collision_matrix.hpp>
#include <impactlab/rigidbody/newton_coulomb_impulse.hpp>

namespace impactlab::rigidbody {

// A contact point between bodies a and b; the normal points from b to a.
struct Contact2D {
  int a = 0, b = 0;          // indices into the body list
  Eigen::Vector2d point;     // world contact point (m)
  Eigen::Vector2d normal;    // unit normal, from b towards a
  double depth = 0.0;        // penetration (m), > 0 when overlapping
  double allowed_approach = 0.0;  // u_n may go down to −this (m/s): a gap
                                  // −depth > 0 that the step of dt closes
                                  // only at this speed is not a contact yet
};

struct PassReport {
  int sweeps = 0;         // full passes over the contact set
  double residual = 0.0;  // max(0, −u_n − allowed approach) over the contacts
                          // at the end (m/s)
};

struct SequentialImpulseSettings {
  double e_n = 0.0;               // collision restitution, [0, 1]
  double mu = 0.5;                // Coulomb friction, >= 0
  int collision_iterations = 10;  // N of GBF's collision pass (5–15)
  int contact_iterations = 20;    // sweeps of the contact pass
  int shock_iterations = 20;      // sweeps per level of shock propagation
  double approach_tolerance = 1e-12;  // u_n below −this counts as approaching, and
                                      // sweeps stop when no velocity changes by more (m/s)
};

// relative normal velocity of a contact, u_n = n·(u_a − u_b) (m/s)
inline double normal_velocity(const std::vector<Body2D>& bodies, const Contact2D& c) {
  const Body2D& a = bodies[c.a];
  const Body2D& b = bodies[c.b];
  const Eigen::Vector2d u =
      a.point_velocity(c.point - a.position) - b.point_velocity(c.point - b.position);
  return c.normal.dot(u);
}

// Applies the Newton–Coulomb impulse of one contact if it approaches.
// Returns the approach speed seen (m/s).
inline double resolve_contact(std::vector<Body2D>& bodies, const Contact2D& c, double e_n,
                              double mu, double tolerance) {
  Body2D& a = bodies[c.a];
  Body2D& b = bodies[c.b];
  const Eigen::Vector2d r_a = c.point - a.position;
  const Eigen::Vector2d r_b = c.point - b.position;
  const Eigen::Vector2d u = a.point_velocity(r_a) - b.point_velocity(r_b);
  if (!(c.normal.dot(u) < -c.allowed_approach - tolerance)) return 0.0;
  const Eigen::Matrix2d K = collision_matrix(a, r_a, b, r_b);
  const auto impulse = newton_coulomb_impulse<2>(K, u, c.normal, {e_n, mu, 0.0});
  if (impulse.regime == ImpulseRegime::inconsistent) return -c.normal.dot(u);
  a.apply_impulse(impulse.impulse, r_a);
  b.apply_impulse(-impulse.impulse, r_b);
  return -c.normal.dot(u);
}

inline double approach_residual(const std::vector<Body2D>& bodies,
                                const std::vector<Contact2D>& contacts) {
  double worst = 0.0;
  for (const auto& c : contacts)
    worst = std::max(worst, -normal_velocity(bodies, c) - c.allowed_approach);
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

// Projected (block) Gauss–Seidel on the contact impulses with a plastic
// target (u_n⁺ = 0, and u_t⁺ = 0 inside the friction cone): each contact
// keeps its accumulated impulse (P_n, P_t); a sweep solves each contact's
// 2×2 block for the impulse that would stop it, projects the accumulated
// impulse onto the cone P_n ≥ 0, |P_t| ≤ μ P_n (on the cone's edge the
// normal velocity is still brought to zero) and applies the change.
// Unlike one-sided impulses, the projection can take back an impulse that a
// later contact made unnecessary, so the sweeps converge to the solution of
// the contact LCP instead of leaving bodies separating (jitter).
// Bodies flagged in `frozen` are static; only contacts with `active` set take
// part. `accumulated` (one (P_n, P_t) per contact, N s) carries the impulses
// over from an earlier pass of the same step: friction can only use the
// normal impulse of the whole step, not of one pass.
inline PassReport projected_gauss_seidel(std::vector<Body2D>& bodies,
                                         const std::vector<Contact2D>& contacts,
                                         const std::vector<char>& active, double mu, int max_sweeps,
                                         double tolerance,
                                         std::vector<Eigen::Vector2d>& accumulated,
                                         const std::vector<char>* frozen = nullptr) {
  PassReport report;
  accumulated.resize(contacts.size(), Eigen::Vector2d::Zero());
  const auto inverse_of = [&](int index, Body2D body) {
    if (frozen && (*frozen)[index]) body.inverse_mass = body.inverse_inertia = 0.0;
    return body;
  };
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    ++report.sweeps;
    double largest_change = 0.0;  // of a contact velocity this sweep (m/s)
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      if (!active[i]) continue;
      const Contact2D& c = contacts[i];
      Body2D a = inverse_of(c.a, bodies[c.a]);
      Body2D b = inverse_of(c.b, bodies[c.b]);
      const Eigen::Vector2d r_a = c.point - a.position, r_b = c.point - b.position;
      const Eigen::Vector2d t(-c.normal.y(), c.normal.x());
      Eigen::Matrix2d frame;  // world from contact coordinates (n, t)
      frame << c.normal, t;
      const Eigen::Matrix2d K = frame.transpose() * collision_matrix(a, r_a, b, r_b) * frame;
      // velocities relative to the target u_n⁺ = −allowed_approach
      const Eigen::Vector2d u = frame.transpose() * (a.point_velocity(r_a) - b.point_velocity(r_b)) +
                                Eigen::Vector2d(c.allowed_approach, 0.0);
      if (!(K(0, 0) > 0.0)) continue;
      // the contact's own 2×2 block solved exactly: sticking target u⁺ = 0,
      // then projected onto the cone (separate, or slide on its edge with
      // u_n⁺ = 0)
      Eigen::Vector2d next = accumulated[i] - K.ldlt().solve(u);
      if (!(next(0) > 0.0)) {
        next.setZero();
      } else if (std::fabs(next(1)) > mu * next(0)) {
        const double sigma = next(1) > 0.0 ? 1.0 : -1.0;
        const Eigen::Vector2d edge(1.0, sigma * mu);
        const double j = (K.row(0).dot(accumulated[i]) - u(0)) / K.row(0).dot(edge);
        next = j > 0.0 ? Eigen::Vector2d(j * edge) : Eigen::Vector2d::Zero();
      }
      const Eigen::Vector2d change = next - accumulated[i];
      accumulated[i] = next;
      const Eigen::Vector2d impulse = frame * change;
      largest_change = std::max(largest_change, (K * change).norm());
      a.apply_impulse(impulse, r_a);
      b.apply_impulse(-impulse, r_b);
      if (!(frozen && (*frozen)[c.a])) bodies[c.a] = a;
      if (!(frozen && (*frozen)[c.b])) bodies[c.b] = b;
    }
    if (largest_change <= tolerance) break;
  }
  report.residual = 0.0;
  for (std::size_t i = 0; i < contacts.size(); ++i)
    if (active[i])
      report.residual = std::max(report.residual,
                                 -normal_velocity(bodies, contacts[i]) - contacts[i].allowed_approach);
  return report;
}

// GBF's contact pass, after the velocities were advanced by the forces:
// puts the resting contacts to rest. GBF ramp a restitution from −1 to 0
// over one-sided sweeps; here the sweeps are projected Gauss–Seidel with
// the plastic target, which converges to the same end state (e = 0)
// without the overshoot of one-sided impulses.
inline PassReport contact_pass(std::vector<Body2D>& bodies, const std::vector<Contact2D>& contacts,
                               const SequentialImpulseSettings& s,
                               std::vector<Eigen::Vector2d>& accumulated) {
  const std::vector<char> all(contacts.size(), 1);
  return projected_gauss_seidel(bodies, contacts, all, s.mu, std::max(1, s.contact_iterations),
                                s.approach_tolerance, accumulated);
}

// Shock propagation: levels[k] lists the bodies of level k, bottom up along
// gravity. Each level's contacts with itself and with the levels below are
// solved with the bodies below frozen (static); its contacts with the bodies
// above wait for their own level. The weight of a stack is so carried down in
// one pass instead of one body per sweep.
inline PassReport shock_propagation(std::vector<Body2D>& bodies,
                                    const std::vector<Contact2D>& contacts,
                                    const std::vector<std::vector<int>>& levels,
                                    const SequentialImpulseSettings& s,
                                    std::vector<Eigen::Vector2d>& accumulated) {
  PassReport report;
  std::vector<char> frozen(bodies.size(), 0);
  for (std::size_t i = 0; i < bodies.size(); ++i) frozen[i] = bodies[i].is_static() ? 1 : 0;
  std::vector<char> in_level(bodies.size(), 0), active(contacts.size(), 0);
  for (const auto& level : levels) {
    std::fill(in_level.begin(), in_level.end(), 0);
    for (int body : level) in_level[body] = 1;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      const Contact2D& c = contacts[i];
      const bool a_here = in_level[c.a], b_here = in_level[c.b];
      active[i] = (a_here && (b_here || frozen[c.b])) || (b_here && frozen[c.a]);
    }
    report.sweeps += projected_gauss_seidel(bodies, contacts, active, s.mu, s.shock_iterations,
                                            s.approach_tolerance, accumulated, &frozen)
                         .sweeps;
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
