"""Arrays inside, xarray at the edge: one checked batch per chunk, one contact state shared by every model and
the derivation, the hook seeing only what was given (rule 3), and the study dataset assembled from arrays."""

import numpy as np
import pytest

import impactlab
from impactlab.model import case_inputs as case_inputs_module
from impactlab.run.assemble import VALIDITY_FILL, _common_time, _integer_flags, _on_time, labelled_dataset
from impactlab.model.case_inputs import CaseInputs
from impactlab.errors import FieldError, ModelInputError
from impactlab.model.registry import get_model

STUDY = {
    "name": "three-models",
    "ball": {"preset": "urethane_tour"},
    "face": {"preset": "steel"},
    "contact": {"friction": 0.4, "restitution": 0.8},
    "impact": {"speed": "40 m/s", "angle": "20 deg"},
    "sweep": {"impact.angle": {"start": "10 deg", "stop": "50 deg", "num": 9}},
    "models": ["maw", "rigid_coulomb", "restitution"],
    "outputs": ["launch_angle", "spin_rate"],
}


def _scene():
    return impactlab.load_study(dict(STUDY, sweep={})).scene


@pytest.fixture
def count_states(monkeypatch):
    calls = []
    real = case_inputs_module.contact_state

    def counting(inputs):
        calls.append(len(next(iter(inputs.values()))))
        return real(inputs)

    monkeypatch.setattr(case_inputs_module, "contact_state", counting)
    return calls


def test_one_contact_state_per_chunk_for_every_model_and_the_derivation(count_states):
    result = impactlab.run_study(STUDY, executor="serial", chunk_size=4)
    assert count_states == [4, 4, 1]  # three chunks of the 9 cases, shared by three hooks and three derivations
    assert np.all(np.isfinite(result["launch_angle"].values))


def test_one_model_on_one_batch_builds_the_state_once(count_states):
    scene = _scene()
    get_model("maw")().compute_arrays(scene, ["launch_angle", "spin_rate"])
    assert count_states == [1]


def test_sharing_the_state_changes_no_result():
    shared = impactlab.run_study(STUDY, executor="serial", chunk_size=4)
    for entry_id in ("maw", "rigid_coulomb", "restitution"):
        model = get_model(entry_id)()
        alone = model.compute(impactlab.study.arrays.case_inputs(impactlab.load_study(STUDY)), ["launch_angle",
                                                                                           "spin_rate"])
        assert np.array_equal(shared["launch_angle"].sel(model=entry_id).values, alone["launch_angle"].values)
        assert np.array_equal(shared["spin_rate"].sel(model=entry_id).values, alone["spin_rate"].values)


def test_the_shared_state_cannot_be_changed_by_a_model():
    batch = CaseInputs(_scene().inputs())
    state = batch.contact_state()
    with pytest.raises(ValueError, match="read-only"):
        state["normal_speed"][0] = 0.0
    with pytest.raises(ValueError, match="read-only"):
        batch["speed"][0] = 1.0


def test_a_view_without_the_geometry_has_its_own_state():
    inputs = _scene().inputs()
    batch = CaseInputs(dict(inputs, spin=300.0))
    without_spin = batch.only(set(inputs) - {"spin"})
    assert without_spin.contact_state() is not batch.contact_state()  # it sees no spin: a different state
    assert batch.only(set(batch)).contact_state() is batch.contact_state()
    assert np.all(without_spin.contact_state()["ball_spin"] == 0.0)


class _Recorder(get_model("rigid_coulomb")):
    """Rigid Coulomb, remembering which inputs its hook was handed. References: none."""

    name = "recorder"
    seen: list = []

    def _compute(self, inputs, outputs):
        type(self).seen.append(set(inputs))
        return super()._compute(inputs, outputs)


def test_rule_3_an_absent_optional_input_is_absent():
    _Recorder.seen = []
    inputs = _scene().inputs()
    inputs.pop("spin", None)
    model = _Recorder()
    model.compute(inputs, ["launch_angle"])
    assert "spin" in model.optional_inputs and "club_mass" in model.optional_inputs
    assert "spin" not in _Recorder.seen[-1]
    assert "club_mass" not in _Recorder.seen[-1] or "club_mass" in inputs
    model.compute(dict(inputs, spin=100.0), ["launch_angle"])
    assert "spin" in _Recorder.seen[-1]


def test_a_batch_is_checked_with_the_vocabularys_messages():
    inputs = _scene().inputs()
    with pytest.raises(FieldError, match="impact.speed"):
        CaseInputs(dict(inputs, speed=-1.0))
    with pytest.raises(ModelInputError, match="different lengths"):
        CaseInputs(dict(inputs, speed=[30.0, 40.0], angle=[0.1, 0.2, 0.3]))
    with pytest.raises(FieldError, match="an input name"):
        CaseInputs(dict(inputs, sped=30.0))
    batch = CaseInputs(dict(inputs, speed=[30.0, 40.0, 50.0]))
    assert batch.n_cases == 3 and batch["angle"].shape == (3,)
    assert batch.slice(1, 3).n_cases == 2 and batch.slice(1, 3) is batch.slice(1, 3)
    assert np.array_equal(batch.slice(1, 3)["speed"], [40.0, 50.0])


def test_histories_on_different_time_axes_are_joined_outer():
    a = {"data": {"normal_force": np.array([[1.0, 2.0, 3.0]])}, "time": np.array([0.0, 1.0, 2.0]), "missing": {}}
    b = {"data": {"normal_force": np.array([[5.0, 6.0]])}, "time": np.array([0.5, 2.0]), "missing": {}}
    c = {"data": {"normal_force": np.array([np.nan])}, "time": None, "missing": {"normal_force": "no histories"}}
    time = _common_time([a["time"], b["time"], c["time"]])
    assert np.array_equal(time, [0.0, 0.5, 1.0, 2.0])
    np.testing.assert_array_equal(_on_time(a, "normal_force", time, True), [[1.0, np.nan, 2.0, 3.0]])
    np.testing.assert_array_equal(_on_time(b, "normal_force", time, True), [[np.nan, 5.0, np.nan, 6.0]])
    assert np.all(np.isnan(_on_time(c, "normal_force", time, True))) and _on_time(c, "normal_force", time,
                                                                                   True).shape == (1, 4)
    assert _common_time([None, None]) is None


def test_the_study_dataset_keeps_its_layout_and_provenance():
    result = impactlab.run_study(STUDY, executor="serial")
    assert result["launch_angle"].dims == ("model", "angle")
    assert list(result["model"].values) == ["maw", "rigid_coulomb", "restitution"]
    assert result["angle"].attrs["units"] == "degree" and result["angle"].values[0] == 10.0
    assert result["validity"].dtype == np.int16 and "flag_meanings" in result["validity"].attrs
    assert result.attrs["numpy_version"] == np.__version__ and result.attrs["study_name"] == "three-models"
    # the cached provenance is a copy each time: changing one result's attributes leaves the next alone
    result.attrs["numpy_version"] = "changed"
    assert impactlab.run_study(STUDY).attrs["numpy_version"] == np.__version__


def test_the_dataset_built_from_its_parts_is_the_one_xarrays_constructor_builds():
    """labelled_dataset skips xarray's merge and alignment: the same variables, order, indexes and encodings."""
    import xarray as xr

    data_vars = {
        "spin_rate": xr.Variable(("model", "club", "time"), np.arange(12.0).reshape(2, 3, 2), {"units": "rpm"}),
        "validity": xr.Variable(("model", "club"), np.array([[1.0, np.nan, 0.0], [0.0, 0.0, 16.0]]),
                                {"flag_meanings": "a b"}, {"dtype": "int16", "_FillValue": VALIDITY_FILL}),
    }
    coords = {"model": xr.Variable("model", ["maw", "rigid_coulomb"], {"long_name": "model"}),
              "club": xr.Variable("club", ["driver", "6_iron", "pw"], {"long_name": "club (sets ...)"}),
              "club_mass": xr.Variable("club", [0.2, 0.25, 0.3], {"units": "kg"}),  # a coordinate without an index
              "time": xr.Variable("time", [0.0, 1e-4], {"units": "s"})}
    attributes = {"title": "t", "plan": "p"}
    built = labelled_dataset(data_vars, coords, attributes)
    public = xr.Dataset(data_vars, coords=coords, attrs=attributes)
    xr.testing.assert_identical(built, public)
    assert list(built.variables) == list(public.variables) and list(built.dims) == list(public.dims)
    assert set(built.xindexes) == set(public.xindexes) == {"model", "club", "time"}
    assert all(built.xindexes[name].equals(public.xindexes[name]) for name in public.xindexes)
    assert built["validity"].encoding == {"dtype": "int16", "_FillValue": VALIDITY_FILL}
    assert built["model"].dtype == public["model"].dtype and built.attrs == attributes
    with pytest.raises(ValueError, match="club"):
        labelled_dataset(data_vars, dict(coords, club=xr.Variable("club", ["a", "b"])), attributes)


def test_validity_flags_are_integers_unless_a_model_left_cases_out():
    whole, encoding = _integer_flags(np.array([[1.0, 16.0], [0.0, 17.0]]))
    assert whole.dtype == np.int16 and whole.tolist() == [[1, 16], [0, 17]] and encoding is None
    partial, encoding = _integer_flags(np.array([[1.0, np.nan]]))
    assert partial.dtype == float and np.isnan(partial[0, 1])  # NaN where absent, stored as int16 with a fill value
    assert encoding == {"dtype": "int16", "_FillValue": VALIDITY_FILL}


def test_a_worker_task_carries_its_own_cases_only(monkeypatch):
    """Pickling the whole study's inputs with every chunk made a 10^6-case run 4x slower on 2 processes."""
    from concurrent.futures import ProcessPoolExecutor

    sizes = []
    real = ProcessPoolExecutor.submit

    def recording(self, function, model, inputs, outputs, chunk, *rest):  # rest: the study's plan, paths flag
        sizes.append({values.size for values in inputs.values()})
        return real(self, function, model, inputs, outputs, chunk, *rest)

    monkeypatch.setattr(ProcessPoolExecutor, "submit", recording)
    result = impactlab.run_study(STUDY, executor="processes", workers=2, chunk_size=4)
    assert sizes and all(size <= {4} | {1} for size in sizes) and len(sizes) == 3 * 3
    assert np.array_equal(result["launch_angle"].values,
                          impactlab.run_study(STUDY, executor="serial")["launch_angle"].values)


def test_validity_is_warned_once_per_flag_for_all_models():
    import warnings

    from impactlab.model.diagnostics import ValidityWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        impactlab.run_study(dict(STUDY, models=["maw", "hertz_mindlin", "rigid_coulomb"]))
    texts = [str(w.message) for w in caught if issubclass(w.category, ValidityWarning)]
    assert len(texts) == 2  # large contact and Dundurs coupling; the rigid model raises neither
    assert all(text.startswith("maw, hertz_mindlin: in 9 of 9 case(s) each ") for text in texts)


def test_validity_messages_count_each_flag_per_model_in_a_result_and_in_one_models_selection():
    import xarray as xr

    from impactlab.model.diagnostics import FLAGS, messages

    large, soft = FLAGS[1][1], FLAGS[2][1]
    # model a: bit 1 in 3 of its 4 cases, bit 2 in 1; model b: bit 1 in 3 (one case not computed: NaN); c: none
    values = np.array([[[1, 1], [0, 3]], [[1, 1], [np.nan, 1]], [[0, 0], [0, 0]]])
    result = xr.Dataset({"validity": (("model", "angle", "friction"), values)}, coords={"model": ["a", "b", "c"]})
    assert messages(result) == [f"a, b: in 3 of 4 case(s) each {large}", f"a: in 1 of 4 case(s) {soft}"]
    assert messages(result.sel(model="a")) == [f"a: in 3 of 4 case(s) {large}", f"a: in 1 of 4 case(s) {soft}"]
    assert messages(result.transpose("angle", "model", "friction")) == messages(result)  # models on any axis
    assert messages(result.fillna(0).astype(np.int16)) == messages(result)  # integer flags, as a run's result
    assert messages(result.sel(model="c")) == [] and messages(result.drop_vars("validity")) == []
    assert messages(result.drop_vars("model"))[0] == f"0, 1: in 3 of 4 case(s) each {large}"  # unlabelled models
    assert messages(result.isel(model=0).drop_vars("model"))[0] == f"model: in 3 of 4 case(s) {large}"


def test_after_impact_asked_for_one_quantity_gives_what_the_full_computation_gives():
    from impactlab.physics.contact import AFTER_IMPACT_OUTPUTS, after_impact, impulse_vector
    from impactlab.testing import reference_inputs_3d

    batch = CaseInputs(reference_inputs_3d())
    state = batch.contact_state()
    raw = get_model("maw")()._compute(batch, frozenset({"normal_impulse", "tangential_impulse", "lateral_impulse"}))
    impulse = impulse_vector(state, raw["normal_impulse"], raw["tangential_impulse"], raw["lateral_impulse"])
    full = after_impact(state, impulse, **batch)
    assert set(full) == AFTER_IMPACT_OUTPUTS
    for name in AFTER_IMPACT_OUTPUTS:
        np.testing.assert_array_equal(after_impact(state, impulse, names={name}, **batch)[name], full[name])
    # with a rolling couple on the ball, whose work counts in the energy lost
    moment = 1e-4 * np.stack([np.ones(batch.n_cases), -np.ones(batch.n_cases)], -1)
    full = after_impact(state, impulse, moment=moment, **batch)
    assert not np.array_equal(full["energy_loss"], after_impact(state, impulse, **batch)["energy_loss"])
    for name in AFTER_IMPACT_OUTPUTS:
        np.testing.assert_array_equal(after_impact(state, impulse, names={name}, moment=moment, **batch)[name],
                                      full[name])


def test_one_launch_plane_per_chunk_for_every_models_derivation(monkeypatch):
    calls = []
    real = case_inputs_module.launch_plane

    def counting(state):
        calls.append(state["normal"].shape[0])
        return real(state)

    monkeypatch.setattr(case_inputs_module, "launch_plane", counting)
    impactlab.run_study(STUDY, executor="serial", chunk_size=4)
    assert calls == [4, 4, 1]  # three chunks of the 9 cases, each shared by the derivations of three models


def test_the_launch_plane_of_a_plate_experiment_is_the_plane_of_the_impact_angle():
    from impactlab.physics.contact import after_impact, impulse_vector

    # a plate experiment: the path along +X, the face normal tilted up by the impact angle in the X-Z plane
    batch = CaseInputs({"speed": 40.0, "angle": [-0.2, 0.1, 0.5], "ball_mass": 0.0459, "ball_radius": 0.02135,
                        "ball_inertia_factor": 0.4})
    plane = batch.launch_plane()
    np.testing.assert_allclose(plane["angle"], [-0.2, 0.1, 0.5], rtol=1e-15)
    np.testing.assert_array_equal(plane["across"], [[0.0, 0.0, 1.0]] * 3)
    assert batch.launch_plane() is plane and not plane["angle"].flags.writeable  # once per batch, read-only
    state = batch.contact_state()
    impulse = impulse_vector(state, np.array([3.0, 3.0, 3.0]), np.array([0.5, 0.5, 0.5]))
    given = after_impact(state, impulse, plane=plane, **batch)
    for name, value in after_impact(state, impulse, **batch).items():
        np.testing.assert_array_equal(given[name], value)


def test_the_shared_state_mapping_cannot_be_rebound_by_a_model():
    """A model replacing an entry (not writing in place) would change the next model's results in a serial run
    only: the mapping is read-only too."""
    batch = CaseInputs(_scene().inputs())
    state = batch.contact_state()
    with pytest.raises(TypeError):
        state["normal_speed"] = 0.5 * state["normal_speed"]


def test_a_scenes_inputs_are_computed_once_and_handed_out_as_new_dicts():
    import attrs

    scene = _scene()
    first = scene.inputs()
    first["speed"] = -1.0  # a caller changing its dict changes no other caller's
    assert scene.inputs()["speed"] == pytest.approx(40.0) and scene.inputs() is not scene.inputs()
    faster = attrs.evolve(scene, impact=attrs.evolve(scene.impact, speed=50.0))  # a new scene: its own inputs
    assert faster.inputs()["speed"] == 50.0 and scene.inputs()["speed"] == pytest.approx(40.0)
