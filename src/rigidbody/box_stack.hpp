// A stack of boxes on the ground, advanced by a time-stepping scheme in the
// style of Guendelman, Bridson & Fedkiw (2003) (sequential_impulse.hpp):
//     1. contacts at the current positions
//     2. collision pass (restitution e_n)
//     3. velocities advanced by gravity over dt
//     4. contact pass (restitution ramped to 0), then shock propagation
//     5. positions advanced with the new velocities
//     6. position correction of what still overlaps
// A time-stepping scheme (not the event loop of simulate/simulator.hpp): with
// many persistent contacts the events would accumulate at every step, which
// is what this family of schemes is made for. Its error is first order in dt.
//
// Contacts: each box k rests on box k − 1 (box 0 on the ground y = 0); the
// two bottom corners of the upper box against the top face of the lower one,
// kept while within `contact_margin` of it; a corner above the face may
// approach it at gap/dt (speculative contact), so that a box is not held up
// by a contact it has not reached. This is the contact generation of a
// stack, not a general collision detector.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include <impactlab/rigidbody/body2d.hpp>
#include <impactlab/rigidbody/sequential_impulse.hpp>

namespace impactlab::rigidbody {

struct BoxStackModel {
  std::vector<Eigen::Vector2d> half_extents;  // (half width, half height) per box (m)
  double gravity = 9.81;                      // (m/s²), along −y
  double contact_margin = 1e-3;               // contacts kept within this gap (m)
  int correction_sweeps = 5;
  SequentialImpulseSettings solver;
};

struct BoxStackStepReport {
  std::size_t contacts = 0;
  PassReport collision, contact, shock;
};

// bodies[0] is the ground (static), bodies[k + 1] is box k
// dt: the step (s), for the approach speed that closes a gap within it
inline std::vector<Contact2D> box_stack_contacts(const BoxStackModel& model,
                                                 const std::vector<Body2D>& bodies, double dt) {
  std::vector<Contact2D> contacts;
  for (std::size_t k = 0; k < model.half_extents.size(); ++k) {
    const int upper = static_cast<int>(k) + 1;
    const int lower = static_cast<int>(k);
    const Eigen::Vector2d h = model.half_extents[k];
    Eigen::Vector2d normal = Eigen::Vector2d::UnitY();
    Eigen::Vector2d face_point = Eigen::Vector2d::Zero();
    if (lower > 0) {
      normal = bodies[lower].rotation() * Eigen::Vector2d::UnitY();
      face_point = bodies[lower].world_point({0.0, model.half_extents[k - 1].y()});
    }
    for (const double side : {-1.0, 1.0}) {
      const Eigen::Vector2d corner = bodies[upper].world_point({side * h.x(), -h.y()});
      const double gap = (corner - face_point).dot(normal);
      if (gap > model.contact_margin) continue;
      contacts.push_back({upper, lower, corner, normal, -gap, std::max(0.0, gap) / dt});
    }
  }
  return contacts;
}

inline BoxStackStepReport box_stack_step(const BoxStackModel& model, std::vector<Body2D>& bodies,
                                         double dt) {
  BoxStackStepReport report;
  const std::vector<Contact2D> contacts = box_stack_contacts(model, bodies, dt);
  report.contacts = contacts.size();
  report.collision = collision_pass(bodies, contacts, model.solver);
  for (auto& body : bodies)
    if (!body.is_static()) body.velocity.y() -= model.gravity * dt;
  std::vector<Eigen::Vector2d> accumulated;  // contact impulses of this step (N s)
  report.contact = contact_pass(bodies, contacts, model.solver, accumulated);
  std::vector<std::vector<int>> levels;
  for (std::size_t k = 1; k < bodies.size(); ++k) levels.push_back({static_cast<int>(k)});
  report.shock = shock_propagation(bodies, contacts, levels, model.solver, accumulated);
  for (auto& body : bodies) {
    body.position += body.velocity * dt;
    body.angle += body.angular_velocity * dt;
  }
  for (int k = 1; k <= model.correction_sweeps; ++k)
    correct_positions(bodies, box_stack_contacts(model, bodies, dt),
                      static_cast<double>(k) / model.correction_sweeps);
  return report;
}

}  // namespace impactlab::rigidbody
