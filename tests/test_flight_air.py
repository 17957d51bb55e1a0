"""One air per shot in one flight call (impactlab.fly's ``conditions`` as arrays, scene.air.Conditions, and
fly_session flying a session whose rows state their own weather in one call), against oracles written apart from
the code: each air flown alone through the plain physics function with SI values typed by hand, the ISO 2533
pressure table, the dry-air ideal gas, and the broadcasting rules of numpy."""

import warnings
from pathlib import Path

import numpy as np
import pytest

import impactlab
from impactlab.data.sessions.reader import read_session
from impactlab.data.sessions.flight import fly_session
from impactlab.errors import FieldError
from impactlab.physics import flight as physics
from impactlab.scene import flight
from impactlab.scene.air import Conditions
from impactlab.units import MPH

RPM = np.pi / 30.0
DATA = Path(__file__).parent / "data" / "vendors"
OUTPUTS = ("carry_distance", "offline_distance", "apex_height", "landing_angle", "flight_time")


def test_two_airs_in_one_call_are_each_air_flown_alone():
    """A 7-iron flown in an array of two airs (every key an array) gives, shot by shot, what the plain integrator
    gives for each air alone, its values converted by hand: 5 degC = 278.15 K, 900 hPa = 90 000 Pa, a 5 mph
    headwind is a wind of -5 mph along the target line, a crosswind of -3 mph blows to the left."""
    result = impactlab.fly("120 mph", "16.3 deg", "7097 rpm", "2 deg", "-1 deg", conditions={
        "temperature": ["5 degC", "35 degC"], "pressure": ["900 hPa", "1030 hPa"], "relative_humidity": [0.2, 0.9],
        "headwind": ["5 mph", "-2 m/s"], "crosswind": ["-3 mph", "4 m/s"]})
    airs = [dict(temperature=278.15, pressure=90000.0, relative_humidity=0.2, wind=(-5 * MPH, -3 * MPH, 0.0)),
            dict(temperature=308.15, pressure=103000.0, relative_humidity=0.9, wind=(2.0, 4.0, 0.0))]
    assert result.carry_distance.shape == (2,)
    for index, air in enumerate(airs):
        alone = physics.fly(120 * MPH, np.radians(16.3), 7097 * RPM, np.radians(2.0), np.radians(-1.0), **air)
        assert float(result.carry_distance[index]) == pytest.approx(alone["carry_distance"], rel=1e-12)
        assert float(result.offline_distance[index]) == pytest.approx(alone["offline_distance"], rel=1e-12)
        assert float(result.apex_height[index]) == pytest.approx(alone["apex_height"], rel=1e-12)
        assert float(result.flight_time[index]) == pytest.approx(alone["flight_time"], rel=1e-12)
        assert float(result.landing_angle[index]) == pytest.approx(np.degrees(alone["landing_angle"]), rel=1e-12)
    # the result says each shot's air, with units; no air_* attribute describes one air any more
    np.testing.assert_allclose(result.air_temperature.values, [278.15, 308.15], rtol=1e-12)
    np.testing.assert_allclose(result.air_pressure.values, [90000.0, 103000.0], rtol=1e-12)
    np.testing.assert_allclose(result.relative_humidity.values, [0.2, 0.9])
    np.testing.assert_allclose(result.headwind.values, [5 * MPH, -2.0], rtol=1e-12)
    np.testing.assert_allclose(result.crosswind.values, [-3 * MPH, 4.0], rtol=1e-12)
    assert result.air_temperature.attrs["units"] == "K" and result.air_density.attrs["units"] == "kg/m^3"
    assert not [key for key in result.attrs if key.startswith("air_") or key.endswith("wind_m_s")]
    assert set(result.data_vars) == set(OUTPUTS)  # the air is a coordinate of each shot, not an output


def test_each_shots_density_is_the_ideal_gas_of_its_air():
    """Dry air (0 % humidity): rho = p / (R_d T), R_d = 287.05 J/(kg K) (ISO 2533); the coordinate says it per
    shot."""
    result = impactlab.fly("150 mph", "12 deg", "3000 rpm", conditions={
        "temperature": [263.15, 313.15], "pressure": [95000.0, 101325.0], "relative_humidity": 0.0})
    np.testing.assert_allclose(result.air_density.values, [95000.0 / (287.05 * 263.15),
                                                           101325.0 / (287.05 * 313.15)], rtol=1e-3)
    assert float(result.carry_distance[1]) > float(result.carry_distance[0])  # thinner air, less drag: longer


def test_a_shot_without_a_pressure_flies_in_the_isa_pressure_of_its_altitude():
    """NaN in a pressure (altitude) array: not given for that shot. ISO 2533 tabulates 89 874.6 Pa at 1000 m; a
    shot with neither flies at sea level, 101 325 Pa."""
    result = impactlab.fly("167 mph", "10.9 deg", "2686 rpm", conditions={
        "pressure": ["1000 hPa", np.nan, np.nan], "altitude": [np.nan, "1000 m", np.nan]})
    np.testing.assert_allclose(result.air_pressure.values, [100000.0, 89874.6, 101325.0], rtol=2e-4)
    denver = impactlab.fly("167 mph", "10.9 deg", "2686 rpm", conditions={"altitude": "1000 m"})
    assert float(result.carry_distance[1]) == float(denver.carry_distance)
    with pytest.raises(FieldError) as caught:
        impactlab.fly("167 mph", "10.9 deg", "2686 rpm", conditions={
            "pressure": [np.nan, "1000 hPa"], "altitude": [np.nan, "100 m"]})
    assert str(caught.value) == ("conditions.altitude[1]: expected either a pressure or an altitude (which sets the "
                                 "ISA pressure), not both, got pressure 100000 Pa and altitude 100 m")


def test_air_arrays_broadcast_with_the_launch_as_numpy_broadcasts():
    """Launch and air of one shape pair shot i with air i; a column of speeds against a row of temperatures is
    their outer product (numpy's rules); shapes that do not broadcast are refused, naming each shape."""
    speeds, temperatures = np.array([55.0, 65.0, 75.0]), np.array([275.0, 290.0, 305.0])
    paired = impactlab.fly(speeds, np.radians(20.0), 5000 * RPM, conditions={"temperature": temperatures})
    assert paired.carry_distance.shape == (3,)
    outer = impactlab.fly(speeds[:, None], np.radians(20.0), 5000 * RPM, conditions={"temperature": temperatures[:2]})
    assert outer.carry_distance.shape == (3, 2) and outer.air_temperature.shape == (3, 2)
    for i, speed in enumerate(speeds):
        for j, temperature in enumerate(temperatures):
            alone = physics.fly(speed, np.radians(20.0), 5000 * RPM, temperature=temperature, pressure=101325.0)
            if i == j:
                assert float(paired.carry_distance[i]) == pytest.approx(alone["carry_distance"], rel=1e-12)
            if j < 2:
                assert float(outer.carry_distance[i, j]) == pytest.approx(alone["carry_distance"], rel=1e-12)
                assert float(outer.air_temperature[i, j]) == temperature
    with pytest.raises(FieldError) as caught:
        impactlab.fly(speeds, 0.3, 500.0, conditions={"temperature": [280.0, 290.0]})
    assert str(caught.value) == ("conditions: expected air values that broadcast with the launch: one value for "
                                 "every shot, or one per shot (an array of the launch's shape), got ball_speed (3,), "
                                 "conditions.temperature (2,)")
    with pytest.raises(FieldError) as caught:
        impactlab.fly(70.0, 0.3, 500.0, conditions={"temperature": [280.0, 290.0], "headwind": [1.0, 2.0, 3.0]})
    assert str(caught.value) == ("conditions.headwind: expected values of one shape, or single values, that "
                                 "broadcast together (one per shot), got temperature (2,), headwind (3,)")


@pytest.mark.parametrize("conditions, message", [
    ({"temperature": ["20 degC", "200 degC"]}, "conditions.temperature[1]: expected an air temperature between -90 "
     "and 60 degC (183.15 and 333.15 K, around the coldest and hottest air measured on Earth: -89.2 and 56.7 degC; "
     "a degF value written as degC lands above), got 473.15 K (given as '200 degC')"),
    ({"temperature": [290.0, 300.0, 10.0]}, "conditions.temperature[2]: expected an air temperature between -90 "
     "and 60 degC"),
    ({"temperature": [290.0, np.nan]}, "conditions.temperature[1]: expected an air temperature between"),
    ({"relative_humidity": [0.5, 60.0]}, "conditions.relative_humidity[1]: expected a relative humidity between 0 "
     "and 1 (a fraction, or e.g. '50 %'), got 60"),
    ({"pressure": ["1013 hPa", "1013 Pa"]}, "conditions.pressure[1]: expected a station pressure between 200 and "
     "1100 hPa (the ISA pressure at 11 000 m is 226 hPa, the highest sea-level pressure recorded 1084 hPa; hPa "
     "written as Pa lands below), got 1013 Pa (given as '1013 Pa')"),
    ({"headwind": [[1.0, 2.0], [3.0, 60.0]]}, "conditions.headwind[1, 1]: expected a wind speed between -50 and 50 "
     "m/s, got 60 m/s"),
    ({"altitude": [0.0, 12000.0]}, "conditions.altitude[1]: expected an altitude between -500 and 11 000 m"),
    ({"temperature": []}, "conditions.temperature: expected an air temperature between"),
])
def test_an_air_element_out_of_range_is_refused_naming_its_index_and_value(conditions, message):
    with pytest.raises(FieldError) as caught:
        impactlab.fly(70.0, 0.3, 500.0, conditions=conditions)
    assert str(caught.value).startswith(message)


def test_one_air_for_every_shot_stays_in_the_attributes_as_before():
    """Scalars keep the attributes of one air (and no per-shot coordinate); an array whose every element is the
    same air is that one air: the same attributes, and bit for bit the same flights."""
    speeds = np.array([50.0, 70.0, 80.0])
    scalar = impactlab.fly(speeds, 0.25, 600.0, conditions={"temperature": "25 degC", "headwind": "2 m/s"})
    assert list(scalar.attrs)[2:8] == ["air_temperature_K", "air_pressure_Pa", "air_relative_humidity",
                                       "air_density_kg_m3", "headwind_m_s", "crosswind_m_s"]
    assert scalar.attrs["air_temperature_K"] == 298.15 and scalar.attrs["headwind_m_s"] == 2.0
    assert not set(scalar.coords)
    same = impactlab.fly(speeds, 0.25, 600.0, conditions={"temperature": ["25 degC"] * 3, "headwind": [2.0] * 3})
    assert same.attrs == scalar.attrs and not set(same.coords)
    for name in OUTPUTS:
        np.testing.assert_array_equal(same[name].values, scalar[name].values)
    # only the wind varies: the air stays an attribute, the wind becomes a coordinate
    windy = impactlab.fly(speeds, 0.25, 600.0, conditions={"temperature": "25 degC", "headwind": [0.0, 2.0, 4.0]})
    assert windy.attrs["air_temperature_K"] == 298.15 and "headwind_m_s" not in windy.attrs
    np.testing.assert_array_equal(windy.headwind.values, [0.0, 2.0, 4.0])
    assert float(windy.carry_distance[1]) == float(scalar.carry_distance[1])


def test_conditions_is_one_value_object_for_one_air_or_many():
    """Equal airs compare (and hash) equal whether given as lists or arrays; the arrays cannot be changed behind
    the frozen object's back; numbers stay floats."""
    one = Conditions(temperature=[280.0, 290.0], headwind=3)
    assert one == Conditions(temperature=np.array([280.0, 290.0]), headwind=3.0)
    assert hash(one) == hash(Conditions(temperature=(280.0, 290.0), headwind=3.0))
    assert one != Conditions(temperature=[280.0, 291.0], headwind=3.0) and one != Conditions(headwind=3.0)
    assert one.shape == (2,) and Conditions().shape == ()
    assert isinstance(one.headwind, float) and isinstance(Conditions(temperature=300).temperature, float)
    with pytest.raises(ValueError):
        one.temperature[0] = 400.0
    with pytest.raises(FieldError) as caught:
        Conditions(temperature=np.array([[290.0, 300.0], [310.0, 350.0]]))
    assert str(caught.value).startswith("temperature[1, 1]: expected an air temperature") and "got 350.0" in str(
        caught.value)


def _garmin_session(tmp_path, temperatures_f):
    """garmin_r50.csv's first shot, once per temperature [degF], its Air Density left empty."""
    lines = (DATA / "garmin_r50.csv").read_text().splitlines()
    header = lines[0].split(",")
    rows = []
    for temperature in temperatures_f:
        cells = lines[2].split(",")
        cells[header.index("Temperature")] = f"{temperature}"
        cells[header.index("Air Density")] = ""
        rows.append(",".join(cells))
    path = tmp_path / "garmin.csv"
    path.write_text("\n".join(lines[:2] + rows) + "\n")
    return path, dict(zip(header, lines[2].split(",")))


def test_a_session_in_many_airs_flies_in_one_call_each_shot_in_its_own_air(tmp_path, monkeypatch):
    """Three shots, each at its own temperature: fly_session calls the integrator once, and each shot's carry is
    the same launch flown alone in that row's air typed in its units (degF, kPa, %)."""
    temperatures = [41.0, 71.6, 95.0]
    path, raw = _garmin_session(tmp_path, temperatures)
    calls = []
    original = flight.physics.fly
    monkeypatch.setattr(flight.physics, "fly", lambda *args, **kwargs: calls.append(1) or original(*args, **kwargs))
    result = fly_session(read_session(path))
    assert len(calls) == 1
    monkeypatch.setattr(flight.physics, "fly", original)
    v = read_session(path).values
    for index, temperature in enumerate(temperatures):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            alone = impactlab.fly(v["ball_speed"][index], v["vertical_launch_angle"][index], v["spin_rate"][index],
                                  v["spin_axis"][index], v["horizontal_launch_angle"][index], conditions={
                                      "temperature": f"{temperature} degF", "pressure": f"{raw['Air Pressure']} kPa",
                                      "relative_humidity": f"{raw['Relative Humidity']} %"})
        assert float(result.carry_distance[index]) == pytest.approx(float(alone.carry_distance), rel=1e-12)
        assert float(result.air_density[index]) == pytest.approx(alone.attrs["air_density_kg_m3"], rel=1e-12)
    assert "air_temperature_K" not in result.attrs  # no one air to state
    assert np.all(np.diff(result.air_density.values) < 0)  # warmer rows: thinner air
    one_air = fly_session(read_session(_garmin_session(tmp_path, [71.6, 71.6])[0]))
    assert one_air.attrs["air_temperature_K"] == pytest.approx((71.6 - 32) / 1.8 + 273.15, rel=1e-12)


def test_a_scene_takes_one_air_and_a_study_block_stays_one_air():
    """A study's scene has one air (the sweep varies it): a Conditions of arrays is refused there, not flown with
    the cases paired to its elements by accident; the YAML block reads numbers with units as before."""
    import attrs

    from impactlab.study.scene_blocks import build_conditions

    scene = impactlab.load_study(
        {"name": "air", "ball": {"preset": "urethane_tour"}, "club": {"preset": "driver"},
         "contact": {"friction": 0.4, "restitution": 0.8}, "conditions": {"temperature": "25 degC"},
         "delivery": {"club_speed": "110 mph", "path": "2 deg", "face_angle": "-1 deg", "attack_angle": "-1 deg",
                      "dynamic_loft": "13 deg"}, "models": ["rigid_coulomb"], "outputs": ["carry_distance"]}).scene
    assert scene.conditions == Conditions(temperature=298.15) and isinstance(scene.conditions.temperature, float)
    with pytest.raises(FieldError) as caught:
        attrs.evolve(scene, conditions=Conditions(temperature=[280.0, 300.0]))
    assert str(caught.value).startswith("conditions: expected one air for the scene")
    assert build_conditions({"temperature": "25 degC"}) == Conditions(temperature=298.15)


@pytest.mark.parametrize("arguments, where", [
    ({"conditions": {"relative_humidity": [True, False]}}, "conditions.relative_humidity"),  # flown as 100 %, 0 %
    ({"conditions": {"headwind": [0.0, True]}}, "conditions.headwind"),  # 1 m/s of wind nobody asked for
    ({"spin_axis": [True, False]}, "spin_axis"),  # 1 rad = 57 deg of tilt, 44 m offline
    ({"spin_axis": np.array([True, False])}, "spin_axis"),
])
def test_true_and_false_in_an_array_are_refused_as_a_lone_true_is(arguments, where):
    # a lone True is refused (quantity_array); in a list numpy reads it as 1.0, a number nobody typed
    with pytest.raises(FieldError, match=rf"^{where}: expected .*\(not True/False\), got "):
        impactlab.fly([70.0, 71.0], 0.3, 500.0, **arguments)


def test_a_list_of_pint_quantities_is_read_as_the_same_list_of_strings():
    # a list of quantities (each with its unit, here an offset unit) was refused as 'not a temperature'
    from impactlab.units import registry

    unit = registry()
    as_text = impactlab.fly(["150 mph", "60 m/s"], "12 deg", "2800 rpm",
                            conditions={"temperature": ["5 degC", "95 degF"]})
    as_pint = impactlab.fly([unit.Quantity(150, "mph"), unit.Quantity(60, "m/s")], "12 deg", "2800 rpm",
                            conditions={"temperature": [unit.Quantity(5, "degC"), unit.Quantity(95, "degF")]})
    np.testing.assert_allclose(as_pint.air_temperature.values, [278.15, 308.15], rtol=1e-12)  # (95 - 32) 5/9 + 273.15
    np.testing.assert_array_equal(as_pint.carry_distance.values, as_text.carry_distance.values)
