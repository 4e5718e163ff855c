"""gyrostat.schema: the strict, declarative validator of TOML scene documents."""

import tomllib

import pytest

from gyrostat.schema import (ArrayOf, Choice, Field, ListOf, Matrix, OneOf, SceneError, Table, Variants, Vector,
                             at_least, describe, increasing, non_negative, positive, validate)

LAW = Variants("kind", {
    "constant": Table({"value": Field(float, required=True, doc="constant value")}),
    "harmonic": Table({
        "mean": Field(float, required=True, doc="mean value"),
        "amplitude": Field(float, default=0, doc="amplitude"),
        "frequency": Field(float, required=True, doc="angular frequency", unit="rad/s", check=positive),
    }),
}, doc="a time law")

BODY = Table({
    "moments": Field(Vector(3), required=True, doc="principal moments A1, A2, A3", unit="kg m^2", check=positive),
    "rotor": Field(Vector(3), default=[0, 0, 0], doc="rotor momentum k", unit="kg m^2/s"),
})

TORQUE = Variants("type", {
    "constant": Table({
        "moment": Field(Vector(3), required=True, doc="torque in body axes", unit="N m"),
        "law": Field(OneOf(float, LAW), default=1.0, doc="scale factor over time"),
    }),
    "linear_damping": Table({
        "matrix": Field(Matrix(3, 3), doc="damping matrix D"),
        "diagonal": Field(Vector(3), doc="diagonal of D"),
    }, one_of=[("matrix", "diagonal")]),
    "viscous_cavity": Table({
        "density": Field(float, required=True, unit="kg/m^3", check=positive),
        "radius": Field(float, unit="m", doc="spherical cavity radius"),
        "p0": Field(float, doc="P = P0 I"),
    }, one_of=[("radius", "p0")]),
    "resistive_medium": Table({
        "coefficients": Field(ListOf(Matrix(3, 3), min_len=1), required=True, doc="D_k of D(t) = sum D_k t^k"),
    }),
})

INITIAL = Table({
    "omega": Field(Vector(3), required=True, doc="angular velocity in body axes", unit="rad/s"),
    "attitude": Field(Vector(4), doc="quaternion (w, x, y, z)"),
})

INTEGRATION = Table({
    "model": Field(Choice("auto", "full", "closed_form"), default="auto", doc="which model to solve"),
    "rtol": Field(float, default=1e-8, check=positive),
    "n_out": Field(int, default=1001, doc="number of output times", check=at_least(2)),
    "t_span": Field(Vector(2), default=[0, 10], unit="s", check=increasing),
    "dense": Field(bool, default=False),
})

OUTPUTS = Table({
    "plots": Field(ListOf(str, choices=["omega", "invariants", "euler_angles"]), default=["omega"]),
    "times": Field(ListOf(float, min_len=2), doc="extra output times", unit="s", check=non_negative),
})

SCENE = Table({
    "title": Field(str, default="", doc="shown on plots"),
    "body": Field(BODY, required=True),
    "torques": Field(ArrayOf(TORQUE), default=[]),
    "initial": Field(INITIAL, required=True),
    "integration": Field(INTEGRATION, default={}),
    "outputs": Field(OUTPUTS, default={}),
})

BASE = """
[body]
moments = [1, 2, 3]
[initial]
omega = [1.0, 0.5, -0.3]
"""


def load(extra: str = "", base: str = BASE) -> dict:
    return tomllib.loads(extra + "\n" + base)


def error(extra: str = "", base: str = BASE, schema=SCENE) -> str:
    with pytest.raises(SceneError) as info:
        validate(schema, load(extra, base))
    message = str(info.value)
    assert "\n" not in message and "Traceback" not in message
    assert len(message) < 300
    return message


# --- valid documents -------------------------------------------------------------------------

def test_defaults_are_filled_and_numbers_normalised():
    scene = validate(SCENE, load())
    assert scene == {
        "title": "",
        "body": {"moments": [1.0, 2.0, 3.0], "rotor": [0.0, 0.0, 0.0]},
        "torques": [],
        "initial": {"omega": [1.0, 0.5, -0.3]},
        "integration": {"model": "auto", "rtol": 1e-8, "n_out": 1001, "t_span": [0.0, 10.0], "dense": False},
        "outputs": {"plots": ["omega"]},
    }
    assert all(type(x) is float for x in scene["body"]["moments"] + scene["body"]["rotor"])
    assert type(scene["integration"]["n_out"]) is int


def test_result_is_a_new_dict_and_defaults_are_not_shared():
    document = load()
    first = validate(SCENE, document)
    first["body"]["rotor"][0] = 5.0
    first["outputs"]["plots"].append("invariants")
    second = validate(SCENE, document)
    assert second["body"]["rotor"] == [0.0, 0.0, 0.0]
    assert second["outputs"]["plots"] == ["omega"]
    assert document["body"]["moments"] == [1, 2, 3]
    assert first["body"] is not document["body"]


def test_ints_accepted_for_floats():
    scene = validate(SCENE, load("[integration]\nrtol = 1\nt_span = [0, 5]"))
    assert scene["integration"]["rtol"] == 1.0 and type(scene["integration"]["rtol"]) is float
    assert scene["integration"]["t_span"] == [0.0, 5.0]


def test_integral_float_accepted_for_int():
    scene = validate(SCENE, load("[integration]\nn_out = 2.0"))
    assert scene["integration"]["n_out"] == 2 and type(scene["integration"]["n_out"]) is int


def test_optional_key_without_default_stays_absent_and_given_one_is_kept():
    assert "attitude" not in validate(SCENE, load())["initial"]
    scene = validate(SCENE, load(base=BASE.replace("omega", "attitude = [1, 0, 0, 0]\nomega")))
    assert scene["initial"]["attitude"] == [1.0, 0.0, 0.0, 0.0]


def test_nested_tables_and_lists():
    scene = validate(SCENE, load('[outputs]\nplots = ["omega", "euler_angles"]\ntimes = [0, 1.5]\n'
                                 '[integration]\nmodel = "full"\ndense = true'))
    assert scene["outputs"] == {"plots": ["omega", "euler_angles"], "times": [0.0, 1.5]}
    assert scene["integration"]["model"] == "full" and scene["integration"]["dense"] is True


def test_variants_and_union_number_or_table():
    scene = validate(SCENE, load("""
[[torques]]
type = "constant"
moment = [0, 0, 1]
law = 0.5
[[torques]]
type = "constant"
moment = [0, 0, 1]
law = { kind = "harmonic", mean = 1, frequency = 2 }
[[torques]]
type = "linear_damping"
diagonal = [1, 2, 3]
[[torques]]
type = "viscous_cavity"
density = 1000
p0 = 0.1
[[torques]]
type = "resistive_medium"
coefficients = [[[1, 0, 0], [0, 1, 0], [0, 0, 1]]]
"""))
    torques = scene["torques"]
    assert torques[0] == {"type": "constant", "moment": [0.0, 0.0, 1.0], "law": 0.5}
    assert torques[1]["law"] == {"kind": "harmonic", "mean": 1.0, "amplitude": 0.0, "frequency": 2.0}
    assert torques[2] == {"type": "linear_damping", "diagonal": [1.0, 2.0, 3.0]}
    assert torques[3] == {"type": "viscous_cavity", "density": 1000.0, "p0": 0.1}
    assert torques[4]["coefficients"] == [[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]]
    assert validate(SCENE, load('[[torques]]\ntype = "constant"\nmoment = [0, 0, 1]'))["torques"][0]["law"] == 1.0


def test_validate_a_variants_schema_and_where():
    assert validate(LAW, {"kind": "constant", "value": 3}) == {"kind": "constant", "value": 3.0}
    with pytest.raises(SceneError, match=r"^law is missing required key 'kind' \(one of: constant, harmonic\)$"):
        validate(LAW, {}, where="law")
    with pytest.raises(SceneError, match=r"^law must be a table, got 3$"):
        validate(LAW, 3, where="law")


# --- unknown keys ----------------------------------------------------------------------------

def test_unknown_key_suggests_the_nearest():
    assert error('[integration]\nmodle = "auto"') == "unknown key 'modle' in [integration]; did you mean 'model'?"
    assert error('titel = "x"') == "unknown key 'titel' at the top level; did you mean 'title'?"


def test_unknown_key_lists_valid_keys_when_nothing_is_close():
    message = error("[body]\nmoments = [1, 2, 3]\nxyz = 1", base="[initial]\nomega = [1, 2, 3]")
    assert message == "unknown key 'xyz' in [body]; valid keys: moments, rotor"


def test_unknown_key_in_array_of_tables_names_index_and_variant():
    message = error('[[torques]]\ntype = "constant"\nmoment = [0, 0, 1]\n'
                    '[[torques]]\ntype = "constant"\nmoment = [0, 0, 1]\nmomnet = 1')
    assert message == "unknown key 'momnet' in [torques[1]] (type = 'constant'); did you mean 'moment'?"


def test_unknown_key_in_table_inside_array():
    message = error('[[torques]]\ntype = "constant"\nmoment = [0, 0, 1]\n'
                    'law = { kind = "harmonic", mean = 1, frequency = 2, frequncy = 3 }')
    assert message == "unknown key 'frequncy' in [torques[0].law] (kind = 'harmonic'); did you mean 'frequency'?"


# --- wrong types -----------------------------------------------------------------------------

def test_string_for_integer():
    assert error('[integration]\nn_out = "10"') == "[integration] n_out must be an integer, got '10' (a string)"


def test_non_integral_float_for_integer():
    assert error("[integration]\nn_out = 2.7") == "[integration] n_out must be an integer, got 2.7"


def test_bool_rejected_for_numbers():
    assert error("[integration]\nn_out = true") == "[integration] n_out must be an integer, got true"
    assert error("[integration]\nrtol = false") == "[integration] rtol must be a number, got false"
    assert error("[integration]\nt_span = [0, true]") == \
        "[integration] t_span must be a list of 2 numbers, got [0, true]"


def test_string_for_float_and_number_for_string_and_bool():
    assert error('[integration]\nrtol = "1e-8"') == "[integration] rtol must be a number, got '1e-8' (a string)"
    assert error("title = 3") == "scene: title must be a string, got 3"
    assert error("[integration]\ndense = 1") == "[integration] dense must be true or false, got 1"


def test_vector():
    assert error('[initial]\nomega = "fast"', base="[body]\nmoments = [1, 2, 3]") == \
        "[initial] omega must be a list of 3 numbers, got 'fast'"
    assert error("[initial]\nomega = [1, 2]", base="[body]\nmoments = [1, 2, 3]") == \
        "[initial] omega must be a list of 3 numbers, got [1, 2] (length 2)"


def test_matrix():
    message = error('[[torques]]\ntype = "linear_damping"\nmatrix = [[1, 0, 0], [0, 1, 0]]')
    assert message == ("[torques[0]] matrix must be a 3x3 matrix (3 lists of 3 numbers), "
                       "got [[1, 0, 0], [0, 1, 0]] (length 2)")


def test_list_of_items_names_the_element():
    message = error('[[torques]]\ntype = "resistive_medium"\ncoefficients = [[[1, 0, 0], [0, 1, 0], [0, 0, 1]], 3]')
    assert message == "[torques[0]] coefficients[1] must be a 3x3 matrix (3 lists of 3 numbers), got 3"
    assert error('[outputs]\ntimes = [0, "a"]') == "[outputs] times[1] must be a number, got 'a'"
    assert error('[[torques]]\ntype = "resistive_medium"\ncoefficients = []') == \
        "[torques[0]] coefficients must be a list of at least 1 3x3 matrices, got [] (length 0)"


def test_list_min_length():
    assert error("[outputs]\ntimes = [1]") == "[outputs] times must be a list of at least 2 numbers, got [1] (length 1)"


def test_list_of_choices():
    assert error('[outputs]\nplots = ["omega", "omgea"]') == \
        "[outputs] plots[1] = 'omgea' is not one of: omega, invariants, euler_angles; did you mean 'omega'?"
    assert error('[outputs]\nplots = "omega"') == "[outputs] plots must be a list of strings, got 'omega'"


def test_choice():
    assert error('[integration]\nmodel = "ful"') == \
        "[integration] model = 'ful' is not one of: auto, full, closed_form; did you mean 'full'?"
    assert error('[integration]\nmodel = "zzz"') == "[integration] model = 'zzz' is not one of: auto, full, closed_form"
    assert error("[integration]\nmodel = 1") == "[integration] model must be one of: auto, full, closed_form; got 1"


def test_table_expected():
    assert error("integration = 3") == "scene: integration must be a table, got 3"
    assert error("torques = 3") == "scene: torques must be an array of tables, got 3"
    assert error("torques = [3]") == "[torques[0]] must be a table, got 3"


def test_union_rejects_other_kinds():
    message = error('[[torques]]\ntype = "constant"\nmoment = [0, 0, 1]\nlaw = "fast"')
    assert message == "[torques[0]] law must be a number or a table, got 'fast'"


# --- missing keys ----------------------------------------------------------------------------

def test_missing_key_gives_its_doc_and_unit():
    assert error(base="[body]\nmoments = [1, 2, 3]\n[initial]") == \
        "[initial] is missing required key 'omega' (angular velocity in body axes [rad/s])"


def test_missing_table():
    assert error(base="[initial]\nomega = [1, 2, 3]") == "missing required table [body]"


def test_missing_key_in_array_of_tables():
    assert error('[[torques]]\ntype = "constant"') == \
        "[torques[0]] is missing required key 'moment' (torque in body axes [N m])"
    assert error('[[torques]]\ntype = "constant"\nmoment = [0, 0, 1]\nlaw = { kind = "harmonic", mean = 1 }') == \
        "[torques[0].law] is missing required key 'frequency' (angular frequency [rad/s])"


# --- variants --------------------------------------------------------------------------------

def test_unknown_discriminator_suggests():
    assert error('[[torques]]\ntype = "constnt"') == (
        "[torques[0]] type = 'constnt' is not one of: constant, linear_damping, viscous_cavity, resistive_medium; "
        "did you mean 'constant'?")


def test_missing_or_mistyped_discriminator():
    assert error("[[torques]]\nmoment = [0, 0, 1]") == ("[torques[0]] is missing required key 'type' "
                                                        "(one of: constant, linear_damping, viscous_cavity, "
                                                        "resistive_medium)")
    assert "[torques[0]] type must be one of: constant" in error("[[torques]]\ntype = 1")


def test_key_of_another_variant_is_unknown():
    message = error('[[torques]]\ntype = "constant"\nmoment = [0, 0, 1]\ndiagonal = [1, 2, 3]')
    assert message == "unknown key 'diagonal' in [torques[0]] (type = 'constant'); valid keys: type, moment, law"


def test_discriminator_of_nested_law():
    message = error('[[torques]]\ntype = "constant"\nmoment = [0, 0, 1]\nlaw = { kind = "harmonc", mean = 1 }')
    assert message == "[torques[0].law] kind = 'harmonc' is not one of: constant, harmonic; did you mean 'harmonic'?"


# --- exactly-one-of groups -------------------------------------------------------------------

def test_one_of_none_given():
    assert error('[[torques]]\ntype = "linear_damping"') == \
        "[torques[0]] needs exactly one of 'matrix' or 'diagonal'; none is given"
    assert error('[[torques]]\ntype = "viscous_cavity"\ndensity = 1') == \
        "[torques[0]] needs exactly one of 'radius' or 'p0'; none is given"


def test_one_of_both_given():
    assert error('[[torques]]\ntype = "viscous_cavity"\ndensity = 1\nradius = 0.1\np0 = 2') == \
        "[torques[0]] needs exactly one of 'radius' or 'p0'; got 'radius' and 'p0'"


# --- hooks -----------------------------------------------------------------------------------

def test_hook_failures():
    assert error("[integration]\nn_out = 1") == "[integration] n_out = 1: must be at least 2"
    assert error("[integration]\nt_span = [5, 1]") == "[integration] t_span = [5, 1]: must be increasing"
    assert error("[body]\nmoments = [1, -2, 3]", base="[initial]\nomega = [1, 2, 3]") == \
        "[body] moments = [1, -2, 3]: must be positive"
    assert error("[outputs]\ntimes = [-1, 2]") == "[outputs] times = [-1, 2]: must not be negative"
    assert error('[[torques]]\ntype = "constant"\nmoment = [0, 0, 1]\n'
                 'law = { kind = "harmonic", mean = 1, frequency = 0 }') == \
        "[torques[0].law] frequency = 0: must be positive"


def test_custom_field_and_table_hooks():
    def even(value):
        if value % 2:
            raise ValueError("must be even,\n  not odd")

    def ordered(table):
        if table["low"] > table["high"]:
            raise ValueError("low must not exceed high")

    schema = Table({"low": Field(int, default=0, check=[even]), "high": Field(int, default=0)}, check=ordered)
    assert validate(schema, {"low": 2, "high": 4}) == {"low": 2, "high": 4}
    with pytest.raises(SceneError, match=r"^limits: low = 3: must be even, not odd$"):
        validate(schema, {"low": 3, "high": 4}, where="limits")
    with pytest.raises(SceneError, match=r"^limits: low must not exceed high$"):
        validate(schema, {"low": 6, "high": 4}, where="limits")
    nested = Table({"limits": Field(schema, required=True)})
    with pytest.raises(SceneError, match=r"^\[limits\]: low must not exceed high$"):
        validate(nested, {"limits": {"low": 6, "high": 4}})


# --- message hygiene -------------------------------------------------------------------------

def test_long_values_are_truncated():
    message = error(f"title = {list(range(10_000))}")
    assert message.startswith("scene: title must be a string, got [0, 1, 2, 3")
    assert message.endswith("...")
    assert len(message) < 120
    message = error('[integration]\nmodel = "' + "x" * 500 + '"')
    assert message == "[integration] model = '" + "x" * 56 + "... is not one of: auto, full, closed_form"


def test_long_unknown_key_and_newlines_are_kept_on_one_line():
    message = error('"a\\nb" = 1')
    assert message == "unknown key 'a\\nb' at the top level; valid keys: title, body, torques, initial, " \
        "integration, outputs"
    long_key = "k" * 200
    assert "..." in error(f"{long_key} = 1")


def test_scene_error_is_a_value_error():
    assert issubclass(SceneError, ValueError)


# --- schema definition and describe ----------------------------------------------------------

def test_bad_schemas_are_rejected_at_definition():
    with pytest.raises(TypeError):
        Field(Vector(3), default=[1, 2])
    with pytest.raises(TypeError):
        Field(float, required=True, default=1.0)
    with pytest.raises(TypeError):
        Table({"a": Field(float, required=True), "b": Field(float)}, one_of=[("a", "b")])
    with pytest.raises(TypeError):
        Table({"a": Field(float)}, one_of=[("a", "c")])
    with pytest.raises(TypeError):
        Field(list)


def test_describe_mentions_every_key():
    text = describe(SCENE)
    for table in (SCENE, BODY, INITIAL, INTEGRATION, OUTPUTS, *TORQUE.variants.values(), *LAW.variants.values()):
        for key in table.fields:
            assert f"`{key}`" in text, key
    for heading in ("[body]", "[[torques]]", "[initial]", "[integration]", "[outputs]", "[torques.law]"):
        assert heading in text
    for name in TORQUE.variants:
        assert f'type = "{name}"' in text
    assert "| `omega` | 3 numbers | required | rad/s | angular velocity in body axes |" in text
    assert "| `rotor` | 3 numbers | default `[0.0, 0.0, 0.0]` | kg m^2/s | rotor momentum k |" in text
    assert "exactly one of `radius`, `p0`" in text
    assert 'one of "auto", "full", "closed_form"' in text
    assert "number or table" in text
