"""The club catalogue: the club-head presets with their sources, every club of a set, the names launch
monitors give clubs, and a user's clubs from their spec sheets.

:data:`CLUB_PRESETS` holds the measured 2020 driver and estimated woods and irons (each with its source text in
:data:`CLUB_SOURCES`); :data:`CLUB_CATALOGUE` every club of a set (driver, 3/5/7 wood, 3-5 hybrid, 3-9 iron and
four wedges) built from published lofts, lies and head masses (:data:`LOFT_SOURCE`, :data:`LIE_SOURCE`,
:data:`MASS_SOURCE`). :func:`club_key` maps a launch monitor's club name to a catalogue key;
:func:`club_from_spec` and :class:`user_clubs` add a user's own clubs. The head itself is
:class:`impactlab.scene.clubs.ClubHead`.
"""

from __future__ import annotations

import math
import re
from typing import Any

import attrs
import numpy as np

from impactlab.errors import FieldError
from impactlab.scene.clubs import INERTIA_AXES, INERTIA_COMPONENTS, ClubHead
from impactlab.scene.materials import FACE_SURFACES, MATERIAL_PRESETS, face_surface
from impactlab.units import to_si


G_CM2 = 1e-7  # kg m^2 per g cm^2
MM = 1e-3

#: Proceedings 49 (2020) 47 (ISEA 2020), https://www.mdpi.com/2504-3900/49/1/47,
#: Table 1, a measured driver head. Its CoM is "expressed in CoF reference frame" (the Centre of Face frame of its
#: Figure 1, which we could not read): we take that frame as the face's, x along the face normal towards the ball (the
#: ball's impact point lies at x = -21.3 mm from its centre, the head's CG at x = -42.3 mm), y up the face, z towards
#: the toe (x, y, z right-handed puts z at the toe of a right-handed head), so the 2.9 mm is along the face, not
#: vertical. The tensor's {C} axes: y vertical (the largest moment, 5679 g cm^2, as a driver's about its vertical axis
#: is, near the USGA limit of 5900), z towards the toe, parallel to the head frame at address. These readings are
#: ours, not the paper's words; the address-frame reading (2.9 mm vertical) would put the CG 10.1 mm up the face and
#: raise centred spin by 19 % (docs/clubs.md, benchmarks/measure_delivery.py).
DRIVER_2020: dict[str, Any] = dict(mass=0.204, center=(1.0, 2.9, 42.3),
                   tensor=[[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]])


def _driver_2020_tensor():
    published = np.array(DRIVER_2020["tensor"])
    order = [2, 1, 0]  # toe <- z, up <- y, target <- x
    return published[np.ix_(order, order)] * G_CM2


_ESTIMATE = ("Estimate, not a measurement: {what}. Moments: {moments}. Mass: {mass}. CG: {cg}. Sources of the "
             "anchors: Golf Digest (Stachura 2008; 2010) quote manufacturers' iron MOIs of 2400-3000 g cm^2 about the "
             "vertical axis (Ping S56 7-iron 2400, K15 3000; a typical cavity back about 2600); R. Maltby (Golf "
             "Club Design, Fitting, Alteration and Repair; ralphmaltby.com) gives a standard 5-iron head of 254 g "
             "with 7 g steps through the set. Lofts and lies: typical manufacturer specifications.")

# -- published iron-head numbers, typed in from their sources (tests/test_club_catalogue.py pins them) -----------
OZ_IN2 = 28.349523125 * 6.4516  # g cm^2 per ounce (mass) inch^2 (1 oz = 28.349523125 g, 1 in^2 = 6.4516 cm^2)
INCH = 25.4  # mm
#: one patent embodiment's set of irons, its 2- and 9-iron (CAMPAU_SOURCE): CG depth behind the striking face [in]
#: and moment of inertia [oz in^2]; the radius of gyration "between 1.271 and 1.291 inch" for the whole set
CAMPAU_1983: dict[str, Any] = {"cg_depth_in": {2: 0.171, 9: 0.114}, "moi_oz_in2": {2: 13.619, 9: 16.423},
                               "gyration_in": (1.271, 1.291)}
CAMPAU_SOURCE = (
    "D. N. Campau (Pepsico), 'Iron-type golf clubs', US 4,420,156 (1983), abstract: 'In one specific embodiment the "
    "center of gravity for clubs 2 through 9 varied from 0.171 to 0.114 inch behind the striking face, the moment of "
    "inertia varied from 13.619 to 16.423 ounce (wt.)-in.2, and the radius of gyration varied between 1.271 and "
    "1.291 inch'; the CG lies 'progressively farther behind the striking face ... as the loft angle ... decreases' and "
    "the moment 'progressively decreases as the loft angle ... decreases', so 0.171 in and 13.619 oz in^2 are the "
    "2-iron's. A patent embodiment: a design's values, not a measurement of a production head. The moment's axis "
    "is not in the abstract: read here as the vertical through the CG, the axis of heel-toe twisting that the "
    "patent's gear effect turns on (our reading). Its masses I/k^2 (239 g and 279 g at k = 1.271 and 1.291 in) agree "
    "with Maltby's standard 240 g 3-iron and 282 g 9-iron within 1 %.")
#: manufacturers' statements of one iron's moment about the vertical axis [g cm^2] (GOLF_DIGEST_SOURCE)
GOLF_DIGEST_IRON_MOI = {"Ping S56 7-iron": 2400.0, "Ping K15 7-iron": 3000.0, "Ping Eye2 (1983)": 2600.0}
GOLF_DIGEST_SOURCE = (
    "Golf Digest: B. Schweigert (Ping) quoted in 'Can an iron be forgiving and aesthetically pleasing?' (2010-09-01): "
    "a Ping S56 7-iron 2,400 g cm^2, a K15 7-iron 3,000; M. Stachura, 'New Looks: Irons MOI' (2008-03-13): Ping's Eye2 "
    "about 2,600, 'only slightly below where the typical cavity-back iron is today': manufacturers' statements, "
    "not independent measurements.")


def campau_iron(number: float) -> tuple[float, float]:
    """CG depth behind the face [mm] and moment of inertia about the vertical axis [g cm^2] of iron ``number``.

    Linear in the club number between the 2- and 9-iron of Campau's patent embodiment (:data:`CAMPAU_1983`), which
    gives the two ends and says both progress through the set: the ends are the patent's, the steps between are
    interpolated (an estimate). ``number`` outside 2-9 is refused (the patent has no wedges).

    References
    ----------
    D. N. Campau, US 4,420,156 (1983), abstract (:data:`CAMPAU_SOURCE`).
    """
    if not 2 <= number <= 9:
        raise FieldError("iron number", "an iron of Campau's set, 2 to 9", number)
    fraction = (number - 2) / 7.0
    depth, moi = CAMPAU_1983["cg_depth_in"], CAMPAU_1983["moi_oz_in2"]
    return ((depth[2] + fraction * (depth[9] - depth[2])) * INCH,
            (moi[2] + fraction * (moi[9] - moi[2])) * OZ_IN2)


def iron_moments(toe: float, number: float) -> tuple[float, float, float]:
    """Moments about the toe, up and target axes [g cm^2] of iron ``number`` (2-9): ``up`` Campau's
    (:func:`campau_iron`), ``toe`` given (an estimate) and ``target`` = up + toe - 200, a perimeter-weighted plate's
    perpendicular-axis sum less a thickness term (an estimate)."""
    up = campau_iron(number)[1]
    return toe, up, up + toe - 200.0


_IRON_HEAD = (
    "CG depth behind the face and the moment about the vertical (up) axis: Campau's patent embodiment (US 4,420,156, "
    "1983; a design's values, not a measured production head), its 2- and 9-iron typed in, the irons between "
    "interpolated in the club number{wedge}; inside Golf Digest's manufacturer figures of 2400-3000 g cm^2 for "
    "7-irons (Ping S56 2400, K15 3000). Estimates: the moments about the toe axis ({toe}) and the target axis (up + "
    "toe - 200 g cm^2, a perimeter-weighted plate), the CG 2 mm towards the heel and {low} mm low. ")


def _iron_source(what: str, number: float, toe: float, low: float, mass: str, wedge: str = "") -> str:
    depth, up = campau_iron(number)
    return (f"Cited and estimated, each said: {what}. Mass {mass}. " + _IRON_HEAD.format(wedge=wedge, toe=f"{toe:g} "
            f"g cm^2", low=f"{low:g}") + f"(CG depth {depth:.2f} mm, up {up:.0f} g cm^2.) " + CAMPAU_SOURCE + " "
            + GOLF_DIGEST_SOURCE)


_CARRIED = "; the wedges carry the 9-iron's values, the patent having no wedges (an estimate)"
CLUB_SOURCES = {
    "driver": (
        "Measured head (measurement): Proceedings 49 (2020) 47, https://www.mdpi.com/2504-3900/49/1/47, Table 1: "
        "mass 204 g, CG [-42.3, 2.9, 1.0] mm from the face centre, inertia tensor [[2843, -733, 530.2], [-733, "
        "5679, 0.5], [530.2, 0.5, 4085]] g cm^2, loft 9.8 deg, bulge 305 mm. The mapping of its axes to toe/up/"
        "target is ours (docs/clubs.md): the CoM 'expressed in CoF reference frame' is read in the face's frame "
        "(x the face normal, y up the face, z to the toe), so the 2.9 mm is along the face (high), not vertical; "
        "read in the address frame (2.9 mm vertical) it would be 10.1 mm up the face and centred spin 19 % higher. "
        "Roll 254 mm and lie 58 deg: typical manufacturer specifications, not "
        "measured on this head. Face Ti-6Al-4V. Restitution gain 0.083: fitted (impactlab fit trackman_tour: maw "
        "0.082 +- 0.018, hertz_mindlin 0.084 +- 0.014) beside the urethane_tour ball's e = 0.787, a model output; it "
        "puts the driver's e at about 0.87, above the USGA's COR limit of 0.830, so it also stands in for what the "
        "models leave out of a driver's smash factor (Proceedings 49 (2020) 47 needed under 3 g more head mass with "
        "e = 0.83; the shaft's share of the club mass is not modelled)."),
    "fairway_wood": _ESTIMATE.format(
        what="a 15 deg 3-wood scaled from the measured driver",
        moments="up 3300, toe 1800, target 1700 g cm^2, the driver's scaled by mass and by (head size)^2 ~ 0.6 "
                "(a 3-wood head of 150-180 cm^3 against 460)",
        mass="212 g, typical of 3-wood heads (manufacturer specifications 205-220 g)",
        cg="25 mm behind the face and 5 mm below its centre (fairway woods put the CG low to launch off the turf)"
        ) + (" Bulge 300 mm, roll 280 mm: typical specifications. Face 17-4PH steel. Restitution gain 0.083: the "
             "calibration's gain of a bulged (wood) face, fitted on driver rows only (no fairway-wood shots with a "
             "published dynamic loft were found): an assumption for this club."),
    "6_iron": _iron_source("a cavity-back 6-iron, 30 deg, lie 62 deg", 6, 800.0, 2.0, "261 g (Maltby: 254 g + 7 g)"),
    "7_iron": _iron_source("a cavity-back 7-iron, 34 deg, lie 62.5 deg", 7, 820.0, 2.0,
                           "268 g (Maltby: 254 g + 2 x 7 g)"),
    "pitching_wedge": _iron_source("a cavity-back pitching wedge, 46 deg, lie 64 deg", 9, 900.0, 1.0,
                                   "289 g (Maltby: 254 g + 5 x 7 g)", _CARRIED),
}


#: face width x height [mm] of each preset: estimates, not measurements (the irons' are the 75 x 45 mm plate of
#: their inertia estimate, the wedge's taller; the woods' those of typical 460 cm^3 and 3-wood faces, inside the
#: USGA's head limits of 127 x 71.12 mm). They bound where a strike may land (scene/plausibility.py).
FACE_SIZES = {"driver": (110.0, 60.0), "fairway_wood": (95.0, 40.0), "6_iron": (75.0, 45.0),
              "7_iron": (75.0, 45.0), "pitching_wedge": (75.0, 50.0)}
CLUB_SOURCES = {key: text + (f" Face {FACE_SIZES[key][0]:.0f} x {FACE_SIZES[key][1]:.0f} mm (heel-toe x sole-crown): "
                             "an estimate, used to refuse strikes off the face.")
                for key, text in CLUB_SOURCES.items()}


def _face(key):
    return {"face_width": FACE_SIZES[key][0] * MM, "face_height": FACE_SIZES[key][1] * MM}


def _iron(mass, moments, loft, lie, center, name, key):
    return ClubHead(mass=mass, inertia=tuple(m * G_CM2 for m in moments),
                    center_of_mass=tuple(c * MM for c in center), loft=math.radians(loft), lie=math.radians(lie),
                    material=MATERIAL_PRESETS["steel"], name=name, source=CLUB_SOURCES[key],
                    surface=FACE_SURFACES["grooved_blasted_steel"], **_face(key))


CLUB_PRESETS: dict[str, ClubHead] = {
    "driver": ClubHead(
        mass=DRIVER_2020["mass"], inertia=_driver_2020_tensor(),
        center_of_mass=tuple(c * MM for c in DRIVER_2020["center"]), loft=math.radians(9.8), lie=math.radians(58.0),
        bulge_radius=0.305, roll_radius=0.254, material=MATERIAL_PRESETS["titanium"],
        surface=FACE_SURFACES["smooth_titanium"],
        name="driver (measured head, 2020)", source=CLUB_SOURCES["driver"], restitution_gain=0.083, **_face("driver")),
    "fairway_wood": ClubHead(
        mass=0.212, inertia=tuple(m * G_CM2 for m in (1800.0, 3300.0, 1700.0)), center_of_mass=(0.0, -0.005, 0.025),
        loft=math.radians(15.0), lie=math.radians(57.0), bulge_radius=0.300, roll_radius=0.280,
        material=MATERIAL_PRESETS["steel"], name="3-wood (estimate)", source=CLUB_SOURCES["fairway_wood"],
        surface=FACE_SURFACES["smooth_steel"],
        restitution_gain=0.083, **_face("fairway_wood")),
    "6_iron": _iron(0.261, iron_moments(800.0, 6), 30.0, 62.0, (-2.0, -2.0, campau_iron(6)[0]),
                    "6-iron (patent CG depth and MOI, rest estimate)", "6_iron"),
    "7_iron": _iron(0.268, iron_moments(820.0, 7), 34.0, 62.5, (-2.0, -2.0, campau_iron(7)[0]),
                    "7-iron (patent CG depth and MOI, rest estimate)", "7_iron"),
    "pitching_wedge": _iron(0.289, iron_moments(900.0, 9), 46.0, 64.0, (-2.0, -1.0, campau_iron(9)[0]),
                            "pitching wedge (the 9-iron's patent values, rest estimate)", "pitching_wedge"),
}


# -- the club catalogue: every club of a set ---------------------------------------------------------------------
#: published numbers the catalogue is built from (tests/test_club_catalogue.py pins them as typed from the sources)
LOFT_SOURCE = ("Lofts: 'Golf Club Loft Chart', tellmemoregolf.com/equipment/clubs/degree-loft-of-golf-clubs/ "
               "(standard lofts: 3 wood 15, 5 wood 19, 7 wood 22, 3/4/5 hybrid 20/23/26, 3-9 iron 21, 24, 27, 30, 34, "
               "38, 42, pitching wedge 46 deg) and golfah.com/golf-club-loft-degree/ (gap, sand and lob wedge 52, 56, "
               "60 deg): manufacturers' typical specifications, not one model's.")
LIE_SOURCE = ("Lies: the TaylorMade P7-MB 3-iron to pitching wedge span 60.5-64 deg (braudesign.ca/bogey_golf/irons/, "
              "a manufacturer specification); the steps between (0.5 deg a club) are interpolated, an estimate; "
              "wedges beyond the pitching wedge as it; hybrids 59-60 and woods 57-58 deg: estimates (typical "
              "specifications). The lie is kept as data (impactlab takes the face's heel-toe line as level at impact).")
MASS_SOURCE = ("Head masses: R. Maltby (ralphmaltby.com, 'weight parameters for club head'): 'the standard or base "
               "head weight for a 5 iron has been around 254 grams with 7 gram increments moving through the set' (a "
               "clubmaker's standard); the same 7 g step continued to the gap and sand wedge, the lob wedge as the "
               "sand wedge, fairway woods 212 g + 5 g a club and hybrids 228 g + 5 g a club: estimates.")
#: standard lofts [deg] (LOFT_SOURCE)
CATALOGUE_LOFTS = {"3_wood": 15.0, "5_wood": 19.0, "7_wood": 22.0, "3_hybrid": 20.0, "4_hybrid": 23.0,
                   "5_hybrid": 26.0, "3_iron": 21.0, "4_iron": 24.0, "5_iron": 27.0, "6_iron": 30.0, "7_iron": 34.0,
                   "8_iron": 38.0, "9_iron": 42.0, "pitching_wedge": 46.0, "gap_wedge": 52.0, "sand_wedge": 56.0,
                   "lob_wedge": 60.0}
#: the irons' place in Maltby's 7 g ladder, 5-iron = 0
_IRON_STEP = {"3_iron": -2, "4_iron": -1, "5_iron": 0, "6_iron": 1, "7_iron": 2, "8_iron": 3, "9_iron": 4,
              "pitching_wedge": 5, "gap_wedge": 6, "sand_wedge": 7, "lob_wedge": 7}
_IRON_ESTIMATE = ("Cited and estimated, each said. " + _IRON_HEAD.format(
    wedge=_CARRIED, toe="the 6-iron's 800 g cm^2 shifted by 20 a club, the wedges from the pitching wedge's 900",
    low="2 (wedges 1)") + "Face: flat steel (17-4PH), rigid-faced (no spring-like gain). " + CAMPAU_SOURCE + " "
    + GOLF_DIGEST_SOURCE + " ")
_WOOD_ESTIMATE = ("Estimate, not a measurement: the 3-wood preset's head (see fairway_wood) with {mass} g; moments "
                  "scaled by the mass; CG 25 mm behind the face and 5 mm low; bulge 300 mm, roll 280 mm; face "
                  "17-4PH; restitution gain 0.083 as the driver's (an assumption for a hollow wood face). ")
_HYBRID_ESTIMATE = ("Estimate, not a measurement: a hybrid head between a fairway wood and an iron: {mass} g, moments "
                    "(1300, 2900, 2200) g cm^2 scaled by the mass, CG 15 mm behind the face and 4 mm low, bulge 300 "
                    "mm and roll 300 mm, face 17-4PH, restitution gain 0.083 as the woods' (an assumption for a "
                    "hollow, thin face). ")


def _catalogue() -> dict[str, ClubHead]:
    clubs = {"driver": CLUB_PRESETS["driver"]}
    lie_iron = {key: 60.5 + 0.5 * (step + 2) for key, step in _IRON_STEP.items()}
    for key in ("gap_wedge", "sand_wedge", "lob_wedge"):
        lie_iron[key] = 64.0
    fairway = CLUB_PRESETS["fairway_wood"]
    for index, key in enumerate(("3_wood", "5_wood", "7_wood")):
        mass = 212.0 + 5.0 * index
        moments = tuple(m * mass / 212.0 for m in (1800.0, 3300.0, 1700.0))
        clubs[key] = attrs.evolve(
            fairway, mass=mass * 1e-3, inertia=tuple(m * G_CM2 for m in moments),
            loft=math.radians(CATALOGUE_LOFTS[key]), lie=math.radians(57.0 + 0.5 * index),
            name=f"{key[0]}-wood (estimate)",
            source=" ".join((_WOOD_ESTIMATE.format(mass=f"{mass:g}"), LOFT_SOURCE, LIE_SOURCE, MASS_SOURCE)))
    for index, key in enumerate(("3_hybrid", "4_hybrid", "5_hybrid")):
        mass = 228.0 + 5.0 * index
        moments = tuple(m * mass / 228.0 for m in (1300.0, 2900.0, 2200.0))
        clubs[key] = ClubHead(
            mass=mass * 1e-3, inertia=tuple(m * G_CM2 for m in moments), center_of_mass=(0.0, -0.004, 0.015),
            loft=math.radians(CATALOGUE_LOFTS[key]), lie=math.radians(59.0 + 0.5 * index), bulge_radius=0.300,
            roll_radius=0.300, material=MATERIAL_PRESETS["steel"], name=f"{key[0]}-hybrid (estimate)",
            source=" ".join((_HYBRID_ESTIMATE.format(mass=f"{mass:g}"), LOFT_SOURCE, LIE_SOURCE, MASS_SOURCE)),
            restitution_gain=0.083, surface=FACE_SURFACES["smooth_steel"])
    for key, step in _IRON_STEP.items():
        mass = 254.0 + 7.0 * step
        wedge = key.endswith("wedge")
        number = min(step + 5, 9)  # Maltby's step 0 is the 5-iron; the wedges carry the 9-iron's values
        toe = 900.0 + 20.0 * (min(step, 7) - 5) if wedge else 800.0 + 20.0 * (step - 1)
        moments = iron_moments(toe, number)
        name = key.replace("_", " ").replace(" iron", "-iron")
        clubs[key] = ClubHead(
            mass=mass * 1e-3, inertia=tuple(m * G_CM2 for m in moments),
            center_of_mass=(-0.002, -0.001 if wedge else -0.002, campau_iron(number)[0] * MM),
            loft=math.radians(CATALOGUE_LOFTS[key]), lie=math.radians(lie_iron[key]),
            material=MATERIAL_PRESETS["steel"], surface=FACE_SURFACES["grooved_blasted_steel"],
            name=f"{name} (the 9-iron's patent values, rest estimate)" if wedge
            else f"{name} (patent CG depth and MOI, rest estimate)",
            source=" ".join((_IRON_ESTIMATE, LOFT_SOURCE, LIE_SOURCE, MASS_SOURCE)))
    # the presets that predate the catalogue: the same numbers, their own source texts
    for key in ("6_iron", "7_iron", "pitching_wedge"):
        clubs[key] = CLUB_PRESETS[key]
    return clubs


#: every club of a set by key (driver, 3/5/7 wood, 3-5 hybrid, 3-9 iron, pitching, gap, sand and lob wedge)
CLUB_CATALOGUE: dict[str, ClubHead] = _catalogue()
for _key, _club in CLUB_CATALOGUE.items():
    CLUB_PRESETS.setdefault(_key, _club)


def club_preset(name: str) -> ClubHead:
    """The club-head preset called ``name``."""
    try:
        return CLUB_PRESETS[name]
    except (KeyError, TypeError):
        raise FieldError("preset", "a club preset name", name, choices=CLUB_PRESETS) from None


_WORDS = {"one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8, "nine": 9}
_WEDGES = {"pw": "pitching_wedge", "pitchingwedge": "pitching_wedge", "pitching": "pitching_wedge",
           "p": "pitching_wedge", "gw": "gap_wedge", "gapwedge": "gap_wedge", "aw": "gap_wedge",
           "approachwedge": "gap_wedge", "uw": "gap_wedge", "sw": "sand_wedge", "sandwedge": "sand_wedge",
           "lw": "lob_wedge", "lobwedge": "lob_wedge",
           # Square Golf's names (real exports: esabine/wedgematrix *-DrivingRange.csv)
           "pwedge": "pitching_wedge", "gwedge": "gap_wedge", "swedge": "sand_wedge", "lwedge": "lob_wedge"}
#: a wedge named by its loft [deg] -> the catalogue wedge nearest that loft (catalogue lofts: 46, 52, 56, 60)
_WEDGE_LOFTS = ((44, 48, "pitching_wedge"), (49, 53, "gap_wedge"), (54, 57, "sand_wedge"), (58, 64, "lob_wedge"))


def club_key(name: str) -> str | None:
    """The catalogue key of a club as launch monitors name it, or None when it names no club of the catalogue.

    Understood: catalogue keys (``7_iron``), ``Driver``/``Dr``/``1w``/``1 Wood``, ``3 Wood``/``3w``/``W3``,
    ``4 Hybrid``/``4h``/``H4``, ``8 Iron``/``8i``/``I8``/``Eisen 8``, ``PW``/``Pitching Wedge``/``P``/``P-Wedge``,
    ``GW``/``AW``/``Gap Wedge``/``G-Wedge``, ``SW``/``S-Wedge``, ``LW``/``L-Wedge`` and wedges by loft (``56°``,
    ``56 Degree``, ``58``: 44-48 deg pitching, 49-53 gap, 54-57 sand, 58-64 lob wedge), case, spaces, dashes and
    underscores aside.
    """
    if not isinstance(name, str):
        return None
    if _norm_name(name) in _USER_NAMES:
        return _USER_NAMES[_norm_name(name)]
    if name in CLUB_PRESETS:
        return name
    text = re.sub(r"[\s_\-.]+", "", name.strip().lower())
    text = text.replace("°", "deg").replace("º", "deg")
    for word, digit in _WORDS.items():
        text = text.replace(word, str(digit))
    key = None
    if text in ("driver", "dr", "d", "1w", "1wood", "w1", "drv"):
        key = "driver"
    elif text in _WEDGES:
        key = _WEDGES[text]
    elif match := re.fullmatch(r"(?:(\d)(?:w|wood|fw)|(?:w|wood|fw)(\d))", text):
        key = f"{match.group(1) or match.group(2)}_wood"
    elif match := re.fullmatch(r"(?:(\d)(?:h|hy|hyb|hybrid|rescue|u|ut|utility)|(?:h|hy|hybrid)(\d))", text):
        key = f"{match.group(1) or match.group(2)}_hybrid"
    elif match := re.fullmatch(r"(?:(\d)(?:i|ir|iron|eisen|fer)|(?:i|iron|eisen|fer)(\d))", text):
        key = f"{match.group(1) or match.group(2)}_iron"
    elif match := re.fullmatch(r"(\d{2})(?:deg|degree|degrees|degreewedge|wedge|w)?", text):
        loft = int(match.group(1))
        key = next((wedge for low, high, wedge in _WEDGE_LOFTS if low <= loft <= high), None)
    return key if key in CLUB_PRESETS else None


# -- a user's club from its spec sheet -------------------------------------------------------------------------
#: keys of a club spec sheet (YAML): what each is, its dimension
SPEC_KEYS = {"name": "text", "names": "list of launch-monitor names", "base": "catalogue club", "source": "text",
             "loft": "angle", "lie": "angle", "mass": "mass", "moi": "inertia", "cg": "length", "bulge": "length",
             "roll": "length", "face": "material", "restitution_gain": "dimensionless",
             "surface": "face surface (a preset's name, or {preset, roughness_slope, roughness, groove_land, "
                        "water_film, effusivity})"}
#: dimension of each field of a spec sheet's surface mapping
_SURFACE_DIMENSIONS = {"roughness_slope": "dimensionless", "roughness": "length", "groove_land": "length",
                       "water_film": "length", "effusivity": "effusivity"}
#: normalised launch-monitor name -> key of a user club (filled by :func:`user_clubs`)
_USER_NAMES: dict[str, str] = {}


def _norm_name(name: str) -> str:
    return re.sub(r"[\s_\-.]+", "", str(name).strip().lower())


def club_from_spec(document: dict, where: str = "club spec") -> tuple[ClubHead, tuple[str, ...]]:
    """A club head from a spec sheet's values (a YAML mapping), and the launch-monitor names it answers to.

    Every dimensional value carries its unit (``loft: 10.5 deg``, ``mass: 203 g``, ``moi: {up: 5200 g cm^2,
    toe: 2900 g cm^2, target: 4000 g cm^2}``, ``cg: {toe: 0 mm, high: 2 mm, depth: 38 mm}``, ``bulge: 305 mm``);
    ``base`` names a catalogue club whose values fill what the sheet leaves out (default: none, then loft, mass,
    moi and cg are needed); ``face`` a material preset (titanium, steel); ``surface`` the face's surface for the
    friction law (a name of ``FACE_SURFACES``, or a mapping of a preset and/or fields with units over the base's).
    """

    if not isinstance(document, dict):
        raise FieldError(where, "a mapping of club spec keys (" + ", ".join(SPEC_KEYS) + ")",
                         "an empty file" if document is None else document)
    for key in document:
        if key not in SPEC_KEYS:
            raise FieldError(f"{where}.{key}", "a key of a club spec", key, choices=SPEC_KEYS)

    def quantity(value, dimension, path):
        try:
            return to_si(value, dimension, path)  # which bare numbers are refused (all but 0) is to_si's to say
        except FieldError:
            if isinstance(value, (int, float)) and not isinstance(value, bool):  # worded for a spec sheet
                example = {"angle": "deg", "mass": "g", "inertia": "g cm^2", "length": "mm"}[dimension]
                raise FieldError(path, f"a value with its unit (e.g. {value} {example})", value) from None
            raise

    base = club_preset(document["base"]) if "base" in document else None
    fields = {}
    if "mass" in document:
        fields["mass"] = quantity(document["mass"], "mass", f"{where}.mass")
    for key in ("loft", "lie"):
        if key in document:
            fields[key] = quantity(document[key], "angle", f"{where}.{key}")
    for key, attribute in (("bulge", "bulge_radius"), ("roll", "roll_radius")):
        if key in document:
            fields[attribute] = quantity(document[key], "length", f"{where}.{key}")
    if "moi" in document:
        moi = document["moi"]
        if not isinstance(moi, dict) or set(moi) - set(INERTIA_COMPONENTS) or not {"toe", "up", "target"} <= set(moi):
            raise FieldError(f"{where}.moi", "moments about the toe, up and target axes (and optionally the "
                             "products toe_up, toe_target, up_target), each with its unit", moi)
        values = {k: quantity(v, "inertia", f"{where}.moi.{k}") for k, v in moi.items()}
        index = {axis: i for i, axis in enumerate(INERTIA_AXES)}
        tensor = np.zeros((3, 3))
        for k, v in values.items():
            a, _, b = k.partition("_")
            tensor[index[a], index[b or a]] = tensor[index[b or a], index[a]] = v
        fields["inertia"] = tensor
    if "cg" in document:
        cg = document["cg"]
        if not isinstance(cg, dict) or set(cg) != {"toe", "high", "depth"}:
            raise FieldError(f"{where}.cg", "the centre of mass from the face centre: toe, high and depth, each with "
                             "its unit", cg)
        fields["center_of_mass"] = tuple(quantity(cg[k], "length", f"{where}.cg.{k}")
                                         for k in ("toe", "high", "depth"))
    if "face" in document:
        if document["face"] not in MATERIAL_PRESETS:
            raise FieldError(f"{where}.face", "a face material", document["face"], choices=MATERIAL_PRESETS)
        fields["material"] = MATERIAL_PRESETS[document["face"]]
    if "restitution_gain" in document:
        fields["restitution_gain"] = quantity(document["restitution_gain"], "dimensionless",
                                              f"{where}.restitution_gain")
    if "surface" in document:
        fields["surface"] = _spec_surface(document["surface"], f"{where}.surface", base.surface if base else None)
    name = str(document.get("name", "user club"))
    source = str(document.get("source", "a user's spec sheet"))
    if base is not None:
        head = attrs.evolve(base, name=name, source=f"{source} (values not given: the {document['base']} "
                                                    f"catalogue club's)", **fields)
    else:
        missing = [key for key, attribute in (("mass", "mass"), ("moi", "inertia"), ("cg", "center_of_mass"),
                                               ("loft", "loft")) if attribute not in fields]
        if missing:
            raise FieldError(where, f"{', '.join(missing)} (or base: a catalogue club that gives them)", "nothing")
        head = ClubHead(name=name, source=source, **fields)
    names = document.get("names", [name])
    if isinstance(names, str) or not all(isinstance(n, str) for n in names):
        raise FieldError(f"{where}.names", "a list of the names launch monitors give this club", names)
    return head, tuple(names)


def _spec_surface(value, where: str, base):
    """A spec sheet's ``surface``: a preset's name, or a mapping of a preset and/or fields, each with its unit."""
    if isinstance(value, str):
        return face_surface(value, {}, base, where, preset_path=where)
    if not isinstance(value, dict) or set(value) - {"preset", *_SURFACE_DIMENSIONS}:
        raise FieldError(where, "a face surface preset's name or a mapping of preset, "
                         + ", ".join(_SURFACE_DIMENSIONS), value, choices=FACE_SURFACES)
    fields = {key: to_si(item, _SURFACE_DIMENSIONS[key], f"{where}.{key}") for key, item in value.items()
              if key != "preset"}
    return face_surface(value.get("preset"), fields, base, where)


class user_clubs:
    """Context manager: clubs from spec sheets answer to their launch-monitor names inside it.

    ``specs``: (head, names) pairs, as :func:`club_from_spec` (or :func:`impactlab.study.club_specs.read_club_spec`
    for a YAML file) gives them. Each club is registered as ``user_N`` in :data:`CLUB_PRESETS` and its names go
    before the catalogue's in :func:`club_key`; both are put back on exit.
    """

    def __init__(self, specs=None):
        self.specs = list(specs or ())
        self.added: list[str] = []
        self.names: dict[str, str] = {}

    def __enter__(self):
        for number, (head, names) in enumerate(self.specs, start=1):
            key = f"user_{number}"
            CLUB_PRESETS[key] = head
            self.added.append(key)
            for name in names:
                self.names[_norm_name(name)] = key
        self.saved = dict(_USER_NAMES)
        _USER_NAMES.update(self.names)
        return self

    def __exit__(self, *exc):
        for key in self.added:
            CLUB_PRESETS.pop(key, None)
        _USER_NAMES.clear()
        _USER_NAMES.update(self.saved)
        return False


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["G_CM2", "MM", "DRIVER_2020", "OZ_IN2", "INCH", "CAMPAU_1983", "CAMPAU_SOURCE", "GOLF_DIGEST_IRON_MOI",
           "GOLF_DIGEST_SOURCE", "campau_iron", "iron_moments", "CLUB_SOURCES", "FACE_SIZES", "CLUB_PRESETS",
           "LOFT_SOURCE", "LIE_SOURCE", "MASS_SOURCE", "CATALOGUE_LOFTS", "CLUB_CATALOGUE", "club_preset",
           "club_key", "SPEC_KEYS", "club_from_spec", "user_clubs"]
