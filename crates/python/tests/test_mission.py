"""Loading, overrides, TOML/dict round trips and located errors."""

from __future__ import annotations

import pytest

import karman
from conftest import EXAMPLE


def test_load_with_overrides_matches_set(example):
    tilted = karman.load(EXAMPLE, overrides={"flight.inclination": 84})
    example.set("flight.inclination", 84)
    assert tilted.overrides == ["flight.inclination=84"]
    assert tilted.to_dict()["flight"]["inclination"] == 84
    assert tilted.to_toml() == example.to_toml()
    assert tilted.simulate().apogee_agl_m == example.simulate().apogee_agl_m


def test_set_after_simulate_flies_the_changed_mission(example):
    """simulate keeps the built models; a set() after it must fly the new inputs, and a copy
    made before the set keeps flying the old ones."""
    first = example.simulate()
    before = example.copy()
    assert example.simulate().to_dict() == first.to_dict(), "the kept models fly the same"
    example.set("rocket.mass", example.to_dict()["rocket"]["mass"] + 2.0)
    heavier = example.simulate()
    assert heavier.apogee_agl_m < first.apogee_agl_m
    assert heavier.to_dict() == karman.load(EXAMPLE, overrides={
        "rocket.mass": before.to_dict()["rocket"]["mass"] + 2.0}).simulate().to_dict()
    assert before.simulate().to_dict() == first.to_dict()
    assert example.simulate(seed=5).seed == 5


def test_set_takes_python_values(example):
    example.set("rocket.parachutes.main.noise", [0, 0, 0])
    example.set("environment.atmosphere.model", "standard")
    data = example.to_dict()
    assert data["rocket"]["parachutes"]["main"]["noise"] == [0, 0, 0]


def test_copy_is_independent(example):
    other = example.copy()
    other.set("rocket.mass", 20.0)
    assert example.to_dict()["rocket"]["mass"] != 20.0
    assert other.to_dict()["rocket"]["mass"] == 20.0


def test_toml_and_dict_round_trips(example):
    text = example.to_toml()
    again = karman.Mission.from_toml(text, path=EXAMPLE)
    assert again.to_toml() == text
    from_data = karman.Mission.from_dict(example.to_dict(), path=EXAMPLE)
    assert from_data.to_toml() == text
    assert from_data.simulate().to_dict() == example.simulate().to_dict()


def test_syntax_error_names_line_and_column(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text("name = \"x\"\n[flight\nrail_length = 5\n")
    with pytest.raises(karman.MissionError, match=r"broken\.toml:2:\d+: TOML syntax error"):
        karman.load(path)


def test_unknown_set_path_is_a_located_error(example):
    before = example.to_toml()
    with pytest.raises(karman.MissionError) as error:
        example.set("flight.inclinatio", 3)
    message = str(error.value)
    assert "example.toml" in message
    assert "--set flight.inclinatio=3" in message
    assert "unknown field `inclinatio`" in message
    assert example.to_toml() == before, "a failed set leaves the mission unchanged"


def test_invalid_value_names_file_line_and_key(tmp_path):
    text = EXAMPLE.read_text().replace("rail_length = ", "rail_length = -", 1)
    path = tmp_path / "negative.toml"
    path.write_text(text)
    line = next(i for i, l in enumerate(text.splitlines(), 1) if "rail_length = -" in l)
    with pytest.raises(karman.MissionError, match=rf"negative\.toml:{line}:\d+: .*rail_length"):
        karman.load(path)


def test_missing_file_and_bad_types(tmp_path):
    with pytest.raises(karman.MissionError, match="cannot read mission file"):
        karman.load(tmp_path / "absent.toml")
    with pytest.raises(TypeError, match="`flight.inclination`"):
        karman.load(EXAMPLE, overrides={"flight.inclination": object()})
    assert issubclass(karman.MissionError, ValueError)


def test_from_toml_messages_name_the_given_path():
    with pytest.raises(karman.MissionError, match=r"inline\.toml:1:1: missing field `environment`"):
        karman.Mission.from_toml("[flight]\nrail_length = 5\n", path="inline.toml")


def test_inspect_gives_arrays(example):
    report = example.inspect(heights=[0.0, 500.0, 1000.0], times=[0.0, 1.0, 2.0])
    assert set(report) == {"environment", "motor", "rocket"}
    environment = report["environment"]
    arrays = [v for v in environment.values() if hasattr(v, "shape")]
    assert arrays and all(a.shape == (3,) for a in arrays)


def test_a_self_referencing_or_deep_dict_is_an_exception_not_a_crash(example):
    """A dict that contains itself, or one nested 10,000 deep, raises ValueError naming the
    depth limit instead of exhausting the stack; so does `set` of such a value."""
    looped = example.to_dict()
    looped["rocket"]["loop"] = looped
    with pytest.raises(ValueError, match="nested more than 64 levels deep"):
        karman.Mission.from_dict(looped, path=EXAMPLE)
    deep = example.to_dict()
    inner = deep["rocket"]
    for _ in range(10_000):
        inner["x"] = {}
        inner = inner["x"]
    with pytest.raises(ValueError, match="nested more than 64 levels deep"):
        karman.Mission.from_dict(deep, path=EXAMPLE)
    cycle = []
    cycle.append(cycle)
    with pytest.raises(ValueError, match="nested more than 64 levels deep"):
        example.set("rocket.mass", cycle)
    # An ordinary mission still converts.
    assert karman.Mission.from_dict(example.to_dict(), path=EXAMPLE).to_toml() == example.to_toml()


def test_solve_finds_the_mass_for_a_target_apogee(example):
    nominal = example.simulate().apogee_agl_m
    target = round(nominal - 100.0)
    result = example.solve({"apogee_agl_m": target}, "rocket.mass")
    assert abs(result["achieved"] - target) <= 0.01
    assert result["value"] > result["nominal"]
    assert result["flights"] == len(result["trials"]) <= 12
    with pytest.raises(karman.MissionError, match="no value of rocket.mass within"):
        example.solve({"apogee_agl_m": 1e6}, "rocket.mass")
    with pytest.raises(karman.MissionError, match="LO < HI"):
        example.solve({"apogee_agl_m": target}, "rocket.mass", bounds=(3.0, 2.0))
