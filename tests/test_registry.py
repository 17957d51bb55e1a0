"""Plugin discovery: entry points, broken and duplicate plugins, unknown names."""

from importlib import metadata

import pytest

from impactlab.model import registry
from impactlab.errors import ModelNotFoundError, PluginWarning


def fake_entry_points(monkeypatch, extra):
    real = list(metadata.entry_points(group=registry.ENTRY_POINT_GROUP))
    fakes = [metadata.EntryPoint(name, value, registry.ENTRY_POINT_GROUP) for name, value in extra]
    monkeypatch.setattr(registry, "_entry_points", lambda: real + fakes)
    registry.refresh()


@pytest.fixture(autouse=True)
def fresh_registry():
    registry.refresh()
    yield
    registry.refresh()


def test_builtins_come_from_entry_points():
    names = {ep.name for ep in metadata.entry_points(group=registry.ENTRY_POINT_GROUP)}
    assert {"maw", "rigid_coulomb", "restitution"} <= names
    assert registry.get_model("maw").__module__ == "impactlab_models.maw"


def test_broken_plugin_warns_and_the_rest_still_load(monkeypatch):
    with pytest.warns(PluginWarning, match="no_such_module_xyz"):
        fake_entry_points(monkeypatch, [("broken", "no_such_module_xyz:Model")])
    assert {"maw", "rigid_coulomb", "restitution"} <= set(registry.available())
    assert "broken" not in registry.available()


def test_duplicate_and_non_model_plugins_warn(monkeypatch):
    with pytest.warns(PluginWarning) as caught:
        fake_entry_points(monkeypatch, [("maw", "impactlab_models.rigid_coulomb:RigidCoulombModel"),
                                        ("notamodel", "json:dumps")])
    text = " ".join(str(w.message) for w in caught)
    assert "not an ImpactModel subclass" in text
    assert registry.get_model("maw").__module__ == "impactlab_models.maw"


def test_unknown_model_lists_choices_and_closest_match():
    with pytest.raises(ModelNotFoundError) as info:
        registry.get_model("rigid_colomb")
    message = str(info.value)
    assert ("Choices: dem_linear, hertz_mindlin, hertz_mindlin_face, hertz_mindlin_lever, hertz_mindlin_slip, maw, "
            "restitution, rigid_coulomb") in message
    assert "did you mean 'rigid_coulomb'" in message


def test_discovery_is_cached(monkeypatch):
    registry.available()
    monkeypatch.setattr(registry, "_entry_points", lambda: [])
    assert "maw" in registry.available()  # cached
    assert registry.refresh() == {}  # refresh rediscovers


def test_options_data_lists_every_option_once_the_models_own_first():
    """The laws several models share are declared once (models._common.BallLawOptions) and inherited; provenance
    and ``impactlab models`` still list every option, once, the model's own before the shared laws."""
    import attrs

    from impactlab.model.registry import get_model

    for name, first in (("maw", "method"), ("hertz_mindlin", "history"), ("dem_linear", "stiffness_ratio")):
        model = get_model(name)(core_radius=0.019)
        listed = list(model.options_dict())
        assert sorted(listed) == sorted(field.name for field in attrs.fields(type(model.options)))
        assert listed[0] == first and listed[-1] == "face_loss"
        assert model.options_dict()["core_radius"] == 0.019
        assert get_model(name).describe()["options"].keys() == model.options_dict().keys()
