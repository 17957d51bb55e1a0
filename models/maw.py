"""Hertz impact with tangential compliance and Coulomb microslip (Maw, Barber & Fawcett), MDR engine."""

from __future__ import annotations

import attrs
import numpy as np

from impactlab.model import HISTORY_LENGTH
from impactlab.validators import check, in_range
from impactlab.errors import ModelInputError
from impactlab.physics import annuli, compliant3d, mdr

from .shared import BallLawOptions, cover_modulus_field, cover_thickness_field
from .shared import INELASTIC, CompliantOptions, HertzTangentialModel, int_at_least, optional_int

METHODS = ("mdr", "annuli")
#: cases solved together; bounds the memory of the spring arrays
BLOCK = 2048


#: default tolerance of each method on |J_t| / (mu J_n)
DEFAULT_TOLERANCE = {"mdr": 1e-4, "annuli": 1e-3}
#: finest tolerance at which cases MDR cannot solve (a damped law; docs/models.md) are re-solved by annular strips
RESOLVE_TOLERANCE = 3e-4


@attrs.frozen
class MawOptions(BallLawOptions, CompliantOptions):
    """Options of ``maw``.

    Parameters
    ----------
    method : str
        ``"mdr"`` (default, fast): method of dimensionality reduction, a row of
        independent springs that reproduces the axisymmetric Mindlin contact of
        an elastic pressure exactly (Popov & Hess 2015); under the hysteretic
        law, cases whose springs break the 3-D Coulomb limit are solved again
        by annular strips (docs/models.md). ``"annuli"`` (faithful to the paper): the
        annular-strip solution of Maw, Barber & Fawcett, a mixed boundary-value
        problem over all rings at every step.
    tolerance : float, optional
        Target error of the tangential impulse. MDR: relative to the smaller
        of its two scales, the Coulomb bound mu J_n and the impulse m_t |V_x|
        that stops the slip, so beta, spin and launch angle are all accurate to
        about the tolerance; the resolution is chosen per case from it, chi and
        psi1 (thin slip annuli at low loft need more springs). Annuli: relative
        to mu J_n. Default 1e-4 for MDR, 1e-3 for annuli (docs/accuracy.md has
        the measured errors).
    springs, rings, steps : int, optional
        Expert resolution that overrides ``tolerance``: MDR springs across the
        half-width of the largest contact, annuli, and uniform time steps over
        the contact (spring or ring entry and exit instants are added to them).
    history_points : int
        Samples of the force histories on the shared time axis (when asked).
    inelastic : str
        How a restitution e < 1 enters. ``"adjusted_speed"`` (default, the
        paper's approach): the elastic problem is solved at the normal speed
        (1 + e) V_z / 2, so the normal impulse is (1 + e) m* V_z.
        ``"hysteretic"``: Hertz contact with Hunt-Crossley damping chosen to
        rebound at e, solved at the real approach speed; the Coulomb limit
        follows the damped normal force.
    rolling_hysteresis : float or str
        Rolling resistance of the viscoelastic cover (:mod:`impactlab.physics.ball_laws`): the normal force
        acts d = (3/16) alpha a(t) ahead of the contact centre, a(t) the Hertz contact radius at each instant
        (Greenwood & Tabor; Johnson 1985, ch. 8), a couple d F_n opposing the relative rolling of ball and
        face. alpha is a number in [0, 1] or ``"restitution"`` for 1 - e_ball^2 (the normal impact is the cover's
        loading-unloading cycle: no free parameter; e_ball = e - club_restitution_gain). Cases with a couple
        take the 3-D kernel. Default 0: no
        couple, the paper's model unchanged.
    cover_thickness, cover_modulus : float
        The ball's construction in the tangential compliance (:func:`impactlab.physics.ball_laws.layered_kappa`):
        a cover of thickness t [m] and Young's modulus E_c [Pa] (the ball's Poisson ratio) over a core of the
        ball's equivalent material, a shear spring in series with Mindlin's; it changes kappa and with it the
        grip. Default t = 0 (and E_c the ball's): the paper's homogeneous ball.
    friction_law : str
        ``"coulomb"`` (default): the ``friction`` input; ``"adhesion"``: the ball-face pair's friction law
        (:mod:`impactlab.physics.friction_laws`; shared.FRICTION_LAW_DOC).
    core_radius, core_shear_modulus, core_specific_gravity, core_loss, core_modes
        The ball's core turning behind its shell (:mod:`impactlab.physics.core_torsion`;
        shared.CORE_TORSION_DOC): core radius [m] (0, the default: a rigid ball, the paper's model),
        shear modulus [Pa] (default the ball's), specific gravity (default the ball's mean density), loss factor
        (0) and the modes kept (default: up to 20 kHz). Cases with a core take the 3-D kernel.
    face_frequency, face_modal_mass, face_loss
        The club face flexing behind the contact (:mod:`impactlab.physics.face_flex`; shared.FACE_FLEX_DOC):
        one modal oscillator of a spring-like face (club_restitution_gain > 0) in series with the Hertz contact,
        the ball's own restitution on it; 0 (the default): a rigid face. Those cases take the 3-D kernel.
    """

    method: str = attrs.field(default="mdr", validator=check(lambda v: v in METHODS,
                                                             f"one of {', '.join(METHODS)}"))
    tolerance: float = attrs.field(validator=in_range(1e-9, 0.1, "a tolerance between 1e-9 and 0.1"))
    springs: int | None = attrs.field(default=None, validator=optional_int(8))
    rings: int | None = attrs.field(default=None, validator=optional_int(4))
    steps: int | None = attrs.field(default=None, validator=optional_int(16))
    history_points: int = attrs.field(default=HISTORY_LENGTH, validator=int_at_least(2))
    inelastic: str = attrs.field(default="adjusted_speed", validator=check(
        lambda v: v in INELASTIC, f"one of {', '.join(INELASTIC)}"))
    #: the cover in the tangential compliance (docs/models.md, "The ball's construction")
    cover_thickness: float = cover_thickness_field()
    cover_modulus: float | None = cover_modulus_field()

    @tolerance.default
    def _default_tolerance(self):
        return DEFAULT_TOLERANCE.get(self.method, 1e-5)

    def resolution(self, chi: float, psi1: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(springs or rings, tolerance not met) for each case with this chi and these psi1."""
        count = self.rings if self.method == "annuli" else self.springs
        if count is not None:  # expert resolution: the tolerance does not enter
            return np.full(psi1.size, count), np.zeros(psi1.size, dtype=bool)
        if self.method == "annuli":
            rings, capped = annuli.resolution(self.tolerance)
            return np.full(psi1.size, rings), np.full(psi1.size, capped)
        return mdr.resolution(self.tolerance, chi, psi1)

    def resolution_3d(self) -> tuple[int, int, bool]:
        """(springs, steps, tolerance not met) of the 3-D kernel: the expert resolution, or the tolerance's."""
        if self.springs is not None:
            return self.springs, self.steps if self.steps is not None else mdr.STEPS_PER_SPRING * self.springs, False
        springs, steps, capped = compliant3d.resolution(self.tolerance)
        return springs, self.steps if self.steps is not None else steps, capped

    def resolution_steps(self, count: int) -> int:
        """Uniform time steps that go with ``count`` springs or rings (unless given)."""
        if self.steps is not None:
            return self.steps
        if self.method == "annuli":
            return max(annuli.ANNULI_MIN_STEPS, annuli.STEPS_PER_ANNULUS * count)
        return mdr.STEPS_PER_SPRING * count

    def expert_resolution(self) -> tuple[int, int] | None:
        """(springs or rings, steps) when either is set by hand, the other following it; else None."""
        count = self.rings if self.method == "annuli" else self.springs
        if count is None and self.steps is None:
            return None
        if count is None:
            count = self.resolution_3d()[0]
        return int(count), int(self.resolution_steps(count))


class MawModel(HertzTangentialModel):
    """Elastic sphere striking a face: Hertz normal contact, Mindlin tangential compliance, Coulomb microslip.

    The normal contact is Hertz's (contact modulus E*, effective mass m*);
    the tangential traction builds up in the stuck centre of the contact and
    slips at its edge, where it may not exceed mu times the local pressure,
    and the whole contact may slip. The tangential problem is solved with the
    method of dimensionality reduction (springs on the equivalent profile
    x^2/R), which is exact for the axisymmetric Mindlin contact of an elastic
    pressure with any loading history (cases of the hysteretic law where it is
    not go to the annular strips), in the universal variables of Maw, Barber & Fawcett:
    chi = (kappa/2) m*/m_t and psi1 = kappa V_x/(mu V_z), kappa = G*/E*.

    Normal restitution: with e < 1 in the scene, option ``inelastic`` picks
    either the approach of Henrikson et al. (2020), the elastic problem at the
    normal speed (1 + e) V_z / 2 so that the normal impulse is (1 + e) m* V_z,
    or a hysteretic (Hunt-Crossley) normal law that rebounds at e.

    Inputs: ball and face materials (a rigid face has 1/E_face = 0), ball
    mass, radius, inertia factor; impact speed and angle; friction; optional
    spin, restitution and club mass. Outputs: impulses, contact time and,
    on request, the normal and tangential force histories [N] on a shared
    time axis.

    References
    ----------
    N. Maw, J. R. Barber, J. N. Fawcett, The oblique impact of elastic spheres, Wear 38 (1976) 101-114.
    N. Maw, J. R. Barber, J. N. Fawcett, The role of elastic tangential compliance in oblique impact,
    J. Lubr. Technol. 103 (1981) 74-80.
    V. L. Popov, M. Hess, Method of Dimensionality Reduction in Contact Mechanics and Friction, Springer (2015).
    E. Henrikson, P. Wood, C. Broadie, T. Nuttall, Proceedings 49 (2020) 27.
    K. H. Hunt, F. R. E. Crossley, J. Appl. Mech. 42 (1975) 440-445.
    """

    name = "maw"
    label = "Hertz + tangential compliance + Coulomb microslip (Maw)"
    references = (
        "N. Maw, J. R. Barber, J. N. Fawcett, The oblique impact of elastic spheres, Wear 38 (1976) 101-114",
        "N. Maw, J. R. Barber, J. N. Fawcett, The role of elastic tangential compliance in oblique impact, "
        "J. Lubr. Technol. 103 (1981) 74-80",
        "V. L. Popov, M. Hess, Method of Dimensionality Reduction in Contact Mechanics and Friction, Springer (2015)",
        "E. Henrikson, P. Wood, C. Broadie, T. Nuttall, The role of friction and tangential compliance on the "
        "resultant launch angle of a golf ball, Proceedings 49 (2020) 27",
    )
    Options = MawOptions

    def reference_options(self, tolerance):
        # both methods solve the same problem; MDR converges fastest, so it sets the reference for both
        return attrs.evolve(self.options, method="mdr", tolerance=tolerance, springs=None, rings=None, steps=None)

    def can_reach(self, tolerance):
        # the hardest case the rule knows: the smallest normalised incidence
        options = attrs.evolve(self.options, tolerance=tolerance)
        return not bool(options.resolution(1.0, np.array([mdr.SMALLEST_SCALE]))[1][0])

    def solves_3d(self):
        return self.options.method != "annuli"

    def _check_dimensions(self, three_d):
        if self.options.method == "annuli" and np.any(three_d):
            raise ModelInputError(
                f"maw with method: annuli solves impacts on one line only, and {int(np.sum(three_d))} case(s) have a "
                "3-D contact (a free club head struck off its centre-of-mass line, a curved face, face_rotation "
                "asked for, or a flexing face: face_frequency on a club with restitution_gain > 0); use method: mdr "
                "for them")

    def _law_3d(self, kappa):
        return {"law": "mdr"}

    def _solve(self, chi, psi1, record, normal, resolution, steps, kappa):
        if self.options.method == "annuli":
            def solve(chi_part, psi_part):
                return annuli.solve_scaled(chi_part, psi_part, rings=resolution, steps=steps, record=record,
                                           normal=normal)
        else:
            def solve(chi_part, psi_part):
                return mdr.solve_scaled(chi_part, psi_part, springs=resolution, steps=steps, record=record,
                                        normal=normal)
        parts = [solve(chi[i:i + BLOCK], psi1[i:i + BLOCK]) for i in range(0, chi.size, BLOCK)]
        joined = {name: np.concatenate([getattr(part, name) for part in parts]) if record else None
                  for name in ("force", "stick_radius")}
        solved = mdr.TangentialSolution(np.concatenate([part.slip_change for part in parts]), parts[0].tau,
                                        joined["force"], joined["stick_radius"], parts[0].steps,
                                        np.concatenate([part.dissipation for part in parts]))
        if self.options.method == "mdr" and parts[0].breaks_3d_limit is not None:
            return self._annuli_where_mdr_fails(solved, np.concatenate([part.breaks_3d_limit for part in parts]),
                                                chi, psi1, record, normal)
        return solved

    def _limit_correction(self, chi, psi1, normal):
        """Annuli minus MDR of the decoupled equivalent (chi, psi1), where MDR breaks the 3-D limit (method mdr).

        The 3-D kernel solves a coupled contact with MDR springs; where the same springs of its decoupled
        equivalent break the 3-D Coulomb limit, the 1-D solver replaces them by annular strips. Adding that
        difference to the 3-D result makes both paths give one answer at a centred strike and the answer
        continuous in strike position; off the line it is a first-order correction (the coupling's effect on the
        correction itself is neglected). Returns (change of the scaled slip change, limit broken).
        """
        change, broken = np.zeros_like(chi), np.zeros(chi.size, dtype=bool)
        if self.options.method != "mdr":
            return change, broken
        for value in np.unique(chi):
            group = np.nonzero(chi == value)[0]
            counts, _ = self.options.resolution(float(value), psi1[group])
            for count in np.unique(counts):
                rows = group[counts == count]
                steps = self.options.resolution_steps(int(count))
                plain = mdr.solve_scaled(chi[rows], psi1[rows], springs=int(count), steps=steps, record=False,
                                         normal=normal)
                if plain.breaks_3d_limit is None or not np.any(plain.breaks_3d_limit):
                    continue
                fixed = self._annuli_where_mdr_fails(plain, plain.breaks_3d_limit, chi[rows], psi1[rows], False,
                                                     normal)
                change[rows] = fixed.slip_change - plain.slip_change
                broken[rows] = plain.breaks_3d_limit
        return change, broken

    def _annuli_where_mdr_fails(self, solved, interior, chi, psi1, record, normal):
        """Re-solve by annular strips the cases where a damped law made an MDR spring slip inside a stuck one.

        MDR represents a 3-D contact only while its slip zone is an annulus at the edge (Popov & Hess 2015);
        with an elastic pressure it always is, but a damped law's Coulomb limit falls fastest at the centre
        during restitution, and there MDR's springs carry a 3-D traction beyond mu p(r) (by up to 30 %,
        benchmarks/bench_hysteretic.py) and miss beta by up to 3e-2. The annular-strip method solves the 3-D
        problem itself, at the rings of the tolerance but at most those of RESOLVE_TOLERANCE (85 rings, about
        0.05 s per case, beta within 1.1e-3 of the converged strips in that band), or at the expert ``rings``;
        a tolerance tighter than RESOLVE_TOLERANCE is flagged ``tolerance_not_met`` on those cases.
        """
        capped = np.zeros(chi.size, dtype=bool)
        if not np.any(interior):
            return attrs.evolve(solved, capped=capped)
        if self.options.rings is not None:
            rings, too_fine = self.options.rings, False
        else:  # at most the rings of RESOLVE_TOLERANCE (85): ~0.05 s per case; a tighter tolerance is flagged
            rings = annuli.resolution(max(self.options.tolerance, RESOLVE_TOLERANCE))[0]
            too_fine = self.options.tolerance < RESOLVE_TOLERANCE
        steps = max(annuli.ANNULI_MIN_STEPS, annuli.STEPS_PER_ANNULUS * rings)
        redo = annuli.solve_scaled(chi[interior], psi1[interior], rings=rings, steps=steps, record=record,
                                   normal=normal)
        slip_change, dissipation = solved.slip_change.copy(), solved.dissipation.copy()
        slip_change[interior], dissipation[interior] = redo.slip_change, redo.dissipation
        force, stick = solved.force, solved.stick_radius
        if record:  # the re-solved histories, on the MDR time grid
            force, stick = force.copy(), stick.copy()
            for row, case in enumerate(np.nonzero(interior)[0]):
                force[case] = np.interp(solved.tau, redo.tau, redo.force[row])
                stick[case] = np.interp(solved.tau, redo.tau, redo.stick_radius[row])
        capped[interior] = too_fine
        return attrs.evolve(solved, slip_change=slip_change, dissipation=dissipation, force=force,
                            stick_radius=stick, breaks_3d_limit=interior, capped=capped)
