#pragma once
// Which of the grid's sums a particle-to-grid pass forms. A step maps everything once (USL, MUSL),
// but two of its passes need only a part: MUSL and XPIC re-map updated particle velocities
// (momentum only), and USAVG maps twice from the same points, unmoved and with unchanged
// velocities, around its first half stress update (Nairn, CMES 4 (2003) 649): the first pass
// needs the mass and momentum (the grid velocity v_n the half update reads), the second only the
// forces of the half-updated stress. Mass, momentum and the contact normals are the same sums in
// both passes, so each is formed once; the contact's node volumes read the points' volumes, which
// the half update changes, so both passes form them. This needs weights that do not follow F
// within the step: linear, GIMP (its windows are kept for the step) and the B-spline; CPDI, whose
// domains follow F, is refused with USAVG (mpm_layout.cpp).
namespace ballista {

enum class P2gPart {
  All,         ///< mass, momentum and forces, and the contact's normals and node volumes
  Momentum,    ///< the momenta m_p v_p only
  Kinematics,  ///< mass, momentum, the contact's normals and node volumes: no forces
  Forces,      ///< forces and the contact's node volumes: mass, momentum and normals are kept
};

constexpr bool maps_mass(P2gPart p) { return p == P2gPart::All || p == P2gPart::Kinematics; }  // and the normals
constexpr bool maps_momentum(P2gPart p) { return p != P2gPart::Forces; }
constexpr bool maps_forces(P2gPart p) { return p == P2gPart::All || p == P2gPart::Forces; }
constexpr bool maps_volume(P2gPart p) { return p != P2gPart::Momentum; }

}  // namespace ballista
