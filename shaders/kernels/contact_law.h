// EDEM's Hertz-Mindlin (no-slip) contact law, stateless (LAMMPS style): the same function runs
// on the GPU and in the CPU twin. docs/engineering.md has the formulas. Conventions:
//   n        unit normal from j to i (the force on i along +n is repulsive)
//   overlap  > 0 in contact
//   v_rel    velocity of i's surface relative to j's at the contact point
//   ri, rj   distances from the body centres to the contact point (rj = 0 for a wall)
#ifndef REPOSE_KERNELS_CONTACT_LAW_H
#define REPOSE_KERNELS_CONTACT_LAW_H

struct ContactOut {
  vec3 force_i;   // on i; j receives -force_i
  vec3 torque_i;
  vec3 torque_j;
  float normal_force;  // signed scalar normal force (negative = attractive)
  float grip_force;    // what friction, rolling and spinning resistance scale with (kFlagCohesionContactFriction)
  vec3 n_x_ft;         // n x Ft: the tangential force's moment per unit lever arm
  float roll_arm;      // mu_r |Fn| when a rolling torque applies, else -1
  float normal_stiffness;  // Hertz secant stiffness Fn_elastic / overlap = 4/3 E* sqrt(R* dn)
};

// Where two surfaces touch, as process_contact (contacts.h) measured it.
struct ContactGeometry {
  vec3 n;               // unit normal from j to i
  float overlap;        // > 0
  float radius_star;    // R* (a wall: R_i)
  float mass_star;      // m* of the two bodies (a wall: m_i)
  float ri;             // i's centre to the contact point (the tangential force's moment arm)
  float rj;             // j's (0 for a wall)
  float lever_i;        // the EDEM rolling torque's levers (body_torque)
  float lever_j;
  float cohesion_lens;  // kFlagCohesionIntersection: the sphere surfaces' intersection area / pi
};

// Torque on one body of a contact: the tangential force's moment about its sphere's centre (r
// from that centre to the contact point), plus EDEM's standard rolling torque mu_r |Fn| x lever
// against the body's own spin when roll_arm >= 0 (lw = |w|, passed in so a gather computes it once
// per body). The lever is r for a sphere; for a clump, |contact point - centre of mass| (EDEM) or
// r (rolling_lever = "sphere"; rolling_lever() in contacts.h). The lean gather calls it again on
// stored (n x Ft, mu_r |Fn|), so stored and recomputed torques are the same bits.
vec3 body_torque(vec3 n_x_ft, float r, float roll_arm, float lever, vec3 w, float lw) {
  precise vec3 t = scale3(n_x_ft, -r);
  if (roll_arm >= 0.0f) {
    if (lw > 0.0f) {
      precise float k = div_rn(-(roll_arm * lever), lw);
      t = t + scale3(w, k);
    }
  }
  return t;
}

// The contact point: i's surface point along -n (ri = its radius less half the overlap).
vec3 contact_point(vec3 xi, vec3 n, float ri) {
  precise vec3 cp = xi - scale3(n, ri);
  return cp;
}

// Whether a rolling torque's lever must be measured from a clump's centre of mass: EDEM's
// constant torque against each body's own spin (the relative torque of LIGGGHTS uses R*).
bool centre_lever(uint flags) {
  uint need = kFlagRollingConstTorque | kFlagBodies;
  uint never = kFlagRollingRelativeOmega | kFlagRollingLeverSphere;
  return (flags & need) == need && (flags & never) == 0u;
}

// LIGGGHTS cdt (rolling_model_cdt.h) rolling torque on i (j receives minus it), exactly as
// LIGGGHTS writes it: mu_r Fn_el lever w / |w| with w = w_i - w_j (a wall's spin is not
// counted), then its component along n removed (the torque has no twist part, but |w| keeps
// the twist spin). roll_arm = mu_r Fn_el, the elastic normal force kn dn; lever = R* for two
// spheres, r_i - dn/2 for a wall. False (and nothing to add) when the two spins are equal.
bool relative_rolling(vec3 w_i, vec3 w_j, float roll_arm, float lever, vec3 n, OUT(vec3) tr) {
  precise vec3 w = w_i - w_j;
  precise float lw = length3(w);
  tr = vec3(0.0f);
  if (!(lw > 0.0f)) return false;
  precise float k = div_rn(-(roll_arm * lever), lw);
  precise vec3 t = scale3(w, k);
  tr = t - scale3(n, dot3(t, n));
  return true;
}

// Extension restitution_velocity (docs/diagnosis.md): the viscoelastic damping of Brilliantov et
// al. / Kuwabara-Kono, F = -A Sn vn with A a material time (s), added to EDEM's damping. Its
// damping grows with the overlap faster than EDEM's, so restitution falls with impact speed
// (1 - e ~ v^(1/5)). Returns 0 when off, leaving EDEM's bytes unchanged.
float viscoelastic_damping(float time_a, float sn, float vn) {
  if (!(time_a > 0.0f)) return 0.0f;
  precise float f = (time_a * sn) * vn;
  return f;
}

// Extension cohesion: EDEM's linear cohesion F = k A on the Hertz contact area A = pi R* dn,
// attractive; pi_k = pi k with k the cohesion energy density (J/m^3). With lens >= 0 the area is
// pi lens instead (LIGGGHTS sjkr, cohesion_intersection_area()). 0 when off.
float linear_cohesion(float pi_k, float radius_star, float overlap, float lens) {
  if (!(pi_k > 0.0f)) return 0.0f;
  if (lens >= 0.0f) {
    precise float f_lens = pi_k * lens;
    return f_lens;
  }
  precise float f = (pi_k * radius_star) * overlap;
  return f;
}

// LIGGGHTS sjkr's cohesion area over pi (cohesion_model_sjkr.h): the disc where the two sphere
// surfaces intersect, a^2 = -(d-r1-r2)(d+r1-r2)(d-r1+r2)(d+r1+r2) / (4 d^2) at centre distance
// d = r1 + r2 - dn, written with r1 + r2 - d = dn; against a wall r^2 - (r - dn)^2 = dn (2r - dn).
// About 2 R* dn for small overlaps: twice EDEM's Hertz area R* dn.
float cohesion_intersection_area(float r1, float r2, float dist, float overlap, bool wall) {
  if (wall) {
    precise float a_wall = overlap * (2.0f * r1 - overlap);
    return a_wall;
  }
  precise float q = ((overlap * ((dist + r1) - r2)) * ((dist - r1) + r2)) * ((dist + r1) + r2);
  precise float a = div_rn(q, (4.0f * dist) * dist);
  return a;
}

// A stored spring (tangential or rolling) turned into the current tangent plane, its length kept.
vec3 turn_into_tangent_plane(vec3 s, vec3 n) {
  precise float old_sq = dot3(s, s);
  precise vec3 p = s - scale3(n, dot3(s, n));
  precise float new_sq = dot3(p, p);
  if (new_sq > 0.0f) {
    precise float keep = sqrt_rn(div_rn(old_sq, new_sq));
    p = scale3(p, keep);
  }
  return p;
}

// EDEM's type C rolling resistance (elastic-plastic spring-dashpot, Ai et al. 2011 model C; the
// EPSD of LIGGGHTS): a rolling spring torque, built from the relative rolling rotation (twist
// about n excluded) with stiffness k_r = 2.25 k_n (mu_r R*)^2, capped at mu_r R* |Fn| (full
// mobilisation), plus a dashpot of eta_r times critical damping, 2 sqrt(I_r k_r), while the
// spring is below the cap. `spring` is the contact's stored torque, turned into the current
// tangent plane with its length kept (as the tangential spring). Returns the torque on i (j
// receives minus it).
vec3 epsd_rolling_torque(vec3 n, vec3 w_i, vec3 w_j, float radius_star, float normal_force,
                         float normal_stiffness, float mu_r, float inertia_r, float eta_r, float dt,
                         INOUT(vec3) spring) {
  precise vec3 w = w_i - w_j;
  precise vec3 w_roll = w - scale3(n, dot3(w, n));
  precise vec3 m = turn_into_tangent_plane(spring, n);
  precise float arm = mu_r * radius_star;
  precise float k_r = (2.25f * normal_stiffness) * (arm * arm);
  precise float k_r_dt = -(k_r * dt);
  m = m + scale3(w_roll, k_r_dt);
  precise float m_max = arm * abs(normal_force);
  precise float len = length3(m);
  precise vec3 t;
  if (len > m_max) {
    // Fully mobilised: the spring slips at the cap; no damping (Ai et al.'s f = 0).
    precise float ratio = div_rn(m_max, len);
    m = scale3(m, ratio);
    t = m;
  } else {
    precise float c_r = -((2.0f * eta_r) * sqrt_rn(inertia_r * k_r));
    t = m + scale3(w_roll, c_r);
  }
  spring = m;
  return t;
}

// Spinning (twisting) friction, as in Chrono's SMC contact: a torque about the contact normal
// against the relative spin s = (w_i - w_j) . n, of magnitude mu_spin R* |Fn|. It is limited so
// that it never reverses the spin within a step: over one step the kick changes a spin by
// dt T / I (integrate.h), so the torque is at most |s| / (2 dt D), with D = sum over the two
// bodies of (entries in its contact list) x (1 / its moment of inertia about n) (the caller's
// `stop_share`, 0 for a wall). Each of a body's contacts then takes at most half its share of
// the stopping torque, so even all of them together cannot turn the spin over. Returns the
// torque on i (j receives minus it); zero without spin.
vec3 spinning_friction_torque(vec3 n, vec3 w_i, vec3 w_j, float mu_spin, float radius_star,
                              float normal_force, float stop_share, float dt) {
  precise vec3 w = w_i - w_j;
  precise float s = dot3(w, n);
  if (!(s > 0.0f || s < 0.0f)) return vec3(0.0f);
  precise float t_cap = (mu_spin * radius_star) * abs(normal_force);
  precise float t_stop = div_rn(abs(s), (2.0f * dt) * stop_share);
  precise float t = min(t_cap, t_stop);
  precise float k = s > 0.0f ? -t : t;
  return scale3(n, k);
}

// The torques of a full contact entry (the lean gather derives the same from the stored entry):
// the tangential force's moment about each sphere's centre, and the rolling torque, EDEM's
// against each body's own spin (lever lever_i, lever_j) or LIGGGHTS cdt's against the relative
// spin (relative_rolling()).
void contact_torques(ContactGeometry g, vec3 w_i, vec3 w_j, bool j_is_wall, uint flags, INOUT(ContactOut) o) {
  bool relative = (flags & kFlagRollingRelativeOmega) != 0u;
  float arm = o.roll_arm;
  float own_arm = relative ? -1.0f : arm;
  float arm_j = j_is_wall ? -1.0f : own_arm;
  precise float lw_i = own_arm >= 0.0f ? length3(w_i) : 0.0f;
  precise float lw_j = arm_j >= 0.0f ? length3(w_j) : 0.0f;
  o.torque_i = body_torque(o.n_x_ft, g.ri, own_arm, g.lever_i, w_i, lw_i);
  o.torque_j = body_torque(o.n_x_ft, g.rj, arm_j, g.lever_j, w_j, lw_j);
  if (arm >= 0.0f && relative) {
    vec3 tr;
    float lever = j_is_wall ? g.ri : g.radius_star;
    if (relative_rolling(w_i, w_j, arm, lever, g.n, tr)) {
      o.torque_i = o.torque_i + tr;
      if (!j_is_wall) o.torque_j = o.torque_j - tr;
    }
  }
}

ContactOut hertz_mindlin(ContactGeometry g, vec3 v_rel, vec3 w_i, vec3 w_j, bool j_is_wall, PairParams pp,
                         float dt, uint flags, INOUT(vec3) shear) {
  ContactOut o;
  vec3 n = g.n;
  float e_star = pp.a.x;
  float g_star = pp.a.y;
  float damping = pp.a.z;  // -2 sqrt(5/6) beta, >= 0
  float mu_s = pp.a.w;
  float mu_r = pp.b.x;

  precise float sqrt_rd = sqrt_rn(g.radius_star * g.overlap);
  precise float sn = 2.0f * e_star * sqrt_rd;
  precise float st = 8.0f * g_star * sqrt_rd;
  // Fn = 4/3 E* sqrt(R*) dn^(3/2), written as dn * sqrt(R* dn)
  precise float fn_elastic = div_rn(4.0f * e_star * sqrt_rd * g.overlap, 3.0f);
  precise float gamma_n = damping * sqrt_rn(sn * g.mass_star);
  precise float gamma_t = damping * sqrt_rn(st * g.mass_star);

  precise float vn = dot3(v_rel, n);
  precise vec3 v_t = v_rel - scale3(n, vn);

  precise float fn = fn_elastic - gamma_n * vn;
  fn = fn - viscoelastic_damping(pp.b.z, sn, vn);
  if ((flags & kFlagClipAttraction) != 0u) fn = max(fn, 0.0f);
  // What friction and the rolling lever see: the net force, or the repulsion before cohesion.
  precise float fn_grip = fn;
  fn = fn - linear_cohesion(pp.b.w, g.radius_star, g.overlap, g.cohesion_lens);
  if ((flags & kFlagCohesionContactFriction) == 0u) fn_grip = fn;

  // Rotate the stored spring into the current tangent plane, keeping its length, then stretch it.
  precise vec3 spring = turn_into_tangent_plane(shear, n) + scale3(v_t, dt);

  precise vec3 f_spring = scale3(spring, -st);
  precise vec3 f_damp = scale3(v_t, -gamma_t);
  precise float ft_max = mu_s * abs(fn_grip);
  precise vec3 ft;
  if ((flags & kFlagCoulombSpringOnly) != 0u) {
    // LIGGGHTS: the cap acts on the spring alone; damping is dropped while sliding.
    precise float fs = length3(f_spring);
    if (fs > ft_max) {
      precise float ratio = div_rn(ft_max, fs);
      spring = scale3(spring, ratio);
      ft = scale3(spring, -st);
    } else {
      ft = f_spring + f_damp;
    }
  } else {
    // EDEM / DEM-Engine: the cap acts on spring + damper; the spring keeps the capped force.
    ft = f_spring + f_damp;
    precise float f = length3(ft);
    if (f > ft_max) {
      precise float ratio = div_rn(ft_max, f);
      ft = scale3(ft, ratio);
      precise float inv_st = div_rn(-1.0f, st);
      spring = scale3(ft, inv_st);
    }
  }
  shear = spring;

  o.n_x_ft = cross3(n, ft);
  o.force_i = scale3(n, fn) + ft;
  o.normal_force = fn;
  o.grip_force = fn_grip;
  bool rolling = (flags & kFlagRollingConstTorque) != 0u && mu_r > 0.0f;
  // EDEM scales the rolling torque with |Fn|; LIGGGHTS cdt with the elastic force kn dn.
  bool relative = (flags & kFlagRollingRelativeOmega) != 0u;
  precise float roll_force = relative ? fn_elastic : abs(fn_grip);
  o.roll_arm = rolling ? mu_r * roll_force : -1.0f;
  o.normal_stiffness = div_rn(4.0f * e_star * sqrt_rd, 3.0f);
  o.torque_i = vec3(0.0f);
  o.torque_j = vec3(0.0f);
  if ((flags & kFlagLeanContacts) == 0u) contact_torques(g, w_i, w_j, j_is_wall, flags, o);
  return o;
}

#endif
