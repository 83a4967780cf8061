"""Reading measured wear: the three forms round trip, conversions are exact and noted, missing
variables stay missing, and every kind of bad data is reported with its file line and column."""

import csv

import numpy as np
import pytest

from fewear.diagnose.tribometer.measured import (
    MeasuredWear,
    read_measured_wear,
    wear_coefficient_samples,
    write_measured_wear,
)
from fewear.errors import FewearInputError

K_m2_N = np.array([2e-13, 3e-13])
PRESSURE_Pa = np.array([1e6, 5e6])
VELOCITY_m_s = np.array([0.1, 1.0])
AREA_m2 = 2.5e-5
DISTANCES_m = np.array([100.0, 250.0, 400.0])


def cumulative_table():
    """Two tests of three readings, V = k F s exactly; columns as the schema names them."""
    rows = []
    for test in range(2):
        load = PRESSURE_Pa[test] * AREA_m2
        for s in DISTANCES_m:
            rows.append({
                "test_id": f"run {test + 1}", "pressure_Pa": PRESSURE_Pa[test],
                "velocity_m_s": VELOCITY_m_s[test], "sliding_distance_m": s,
                "wear_volume_m3": K_m2_N[test] * load * s, "time_s": s / VELOCITY_m_s[test],
                "normal_load_N": load, "friction_coefficient": 0.1 + 0.01 * test,
                "temperature_C": 25.0 + s / 100.0,
            })
    return rows


def write_csv(path, rows, columns=None, comments=("made by the test",)):
    columns = columns or list(rows[0])
    with open(path, "w", newline="") as stream:
        for comment in comments:
            stream.write(f"# {comment}\n")
        writer = csv.writer(stream)
        writer.writerow(columns)
        for row in rows:
            writer.writerow([row[name] if isinstance(row[name], str) else repr(row[name])
                             for name in columns])
    return path


def column(rows, name):
    return np.array([row[name] for row in rows])


def test_cumulative_volume_round_trip(tmp_path):
    rows = cumulative_table()
    data = read_measured_wear(write_csv(tmp_path / "wear.csv", rows))
    assert data.data_kind == "cumulative_volume"
    assert data.notes == ()
    assert data.available == ("pressure_Pa", "velocity_m_s", "sliding_distance_m",
                              "wear_volume_m3", "time_s", "normal_load_N",
                              "friction_coefficient", "temperature_C")
    assert list(data.test_id) == [row["test_id"] for row in rows]
    for name in data.available:
        np.testing.assert_array_equal(getattr(data, name), column(rows, name))
    assert list(data.line_number) == [3, 4, 5, 6, 7, 8]
    assert [list(index) for index in data.tests()] == [[0, 1, 2], [3, 4, 5]]


def test_writer_and_reader_round_trip(tmp_path):
    rows = cumulative_table()
    original = read_measured_wear(write_csv(tmp_path / "a.csv", rows))
    write_measured_wear(tmp_path / "b.csv", original, comment="copy\nof a.csv")
    copy = read_measured_wear(tmp_path / "b.csv")
    assert copy.available == original.available
    for name in original.available:
        np.testing.assert_array_equal(getattr(copy, name), getattr(original, name))
    assert (tmp_path / "b.csv").read_text().startswith("# copy\n# of a.csv\n")


def test_spreadsheet_export_with_byte_order_mark_and_crlf(tmp_path):
    path = write_csv(tmp_path / "excel.csv", cumulative_table())
    path.write_bytes(b"\xef\xbb\xbf" + path.read_text().replace("\n", "\r\n").encode())
    data = read_measured_wear(path)
    np.testing.assert_array_equal(data.wear_volume_m3, column(cumulative_table(), "wear_volume_m3"))


def test_tests_are_listed_in_order_of_appearance(tmp_path):
    rows = cumulative_table()
    interleaved = [rows[3], rows[0], rows[4], rows[1]]
    data = read_measured_wear(write_csv(tmp_path / "wear.csv", interleaved))
    assert data.test_names() == ["run 2", "run 1"]
    assert [list(index) for index in data.tests()] == [[0, 2], [1, 3]]


def test_samples_recover_k_of_exact_archard_data(tmp_path):
    data = read_measured_wear(write_csv(tmp_path / "wear.csv", cumulative_table()))
    pressure, velocity, k = wear_coefficient_samples(data)
    np.testing.assert_array_equal(pressure, PRESSURE_Pa)
    np.testing.assert_array_equal(velocity, VELOCITY_m_s)
    np.testing.assert_allclose(k, K_m2_N, rtol=1e-12)


def test_samples_are_the_least_squares_slope_through_the_origin(tmp_path):
    rows = cumulative_table()[:3]
    volumes = [1.0e-9, 3.0e-9, 4.0e-9]
    for row, volume in zip(rows, volumes):
        row["wear_volume_m3"] = volume
    _, _, k = wear_coefficient_samples(read_measured_wear(write_csv(tmp_path / "w.csv", rows)))
    fs = PRESSURE_Pa[0] * AREA_m2 * DISTANCES_m
    expected = np.dot(fs, volumes) / np.dot(fs, fs)
    np.testing.assert_allclose(k, [expected], rtol=1e-12)


def test_mass_loss_with_density_argument_converts_exactly(tmp_path):
    rows = cumulative_table()
    density = 8.0e3
    for row in rows:
        row["mass_loss_kg"] = row.pop("wear_volume_m3") * density
    data = read_measured_wear(write_csv(tmp_path / "mass.csv", rows), density_kg_m3=density)
    assert data.data_kind == "mass_loss"
    np.testing.assert_array_equal(data.wear_volume_m3, column(rows, "mass_loss_kg") / density)
    assert len(data.notes) == 1 and "mass_loss_kg" in data.notes[0] and "8000" in data.notes[0]


def test_mass_loss_with_density_column_converts_exactly(tmp_path):
    rows = cumulative_table()
    for row in rows:
        row["density_kg_m3"] = 7.5e3
        row["mass_loss_kg"] = row.pop("wear_volume_m3") * 7.5e3
    data = read_measured_wear(write_csv(tmp_path / "mass.csv", rows))
    np.testing.assert_array_equal(data.wear_volume_m3, column(rows, "mass_loss_kg") / 7.5e3)
    assert "density_kg_m3 column" in data.notes[0]
    with pytest.raises(FewearInputError, match="density_kg_m3.*once"):
        read_measured_wear(tmp_path / "mass.csv", density_kg_m3=7.5e3)


def test_mass_loss_without_density_is_an_error(tmp_path):
    rows = cumulative_table()
    for row in rows:
        row["mass_loss_kg"] = row.pop("wear_volume_m3") * 8e3
    with pytest.raises(FewearInputError, match="line 2, column mass_loss_kg: .*density"):
        read_measured_wear(write_csv(tmp_path / "mass.csv", rows))


def specific_rate_rows():
    return [
        {"test_id": f"S{i}", "pressure_Pa": PRESSURE_Pa[i], "velocity_m_s": VELOCITY_m_s[i],
         "normal_load_N": PRESSURE_Pa[i] * AREA_m2, "sliding_distance_m": 500.0 + 100 * i,
         "specific_wear_rate_m3_N_m": K_m2_N[i]}
        for i in range(2)
    ]


def test_specific_wear_rate_converts_to_volume_and_back(tmp_path):
    rows = specific_rate_rows()
    data = read_measured_wear(write_csv(tmp_path / "rate.csv", rows))
    assert data.data_kind == "specific_wear_rate"
    expected = K_m2_N * column(rows, "normal_load_N") * column(rows, "sliding_distance_m")
    np.testing.assert_allclose(data.wear_volume_m3, expected, rtol=1e-15)
    assert "V = k F s" in data.notes[0]
    assert data.time_s is None and data.friction_coefficient is None
    _, _, k = wear_coefficient_samples(data)
    np.testing.assert_allclose(k, K_m2_N, rtol=1e-14)


def test_specific_wear_rate_needs_one_row_per_test_and_a_load(tmp_path):
    rows = specific_rate_rows()
    rows[1]["test_id"] = "S0"
    with pytest.raises(FewearInputError, match="line 4, column test_id: test S0 appears again"):
        read_measured_wear(write_csv(tmp_path / "rate.csv", rows))
    columns = [name for name in specific_rate_rows()[0] if name != "normal_load_N"]
    with pytest.raises(FewearInputError, match="column normal_load_N: missing"):
        read_measured_wear(write_csv(tmp_path / "rate.csv", specific_rate_rows(), columns))


def test_missing_variables_stay_none(tmp_path):
    columns = ["test_id", "normal_load_N", "sliding_distance_m", "wear_volume_m3"]
    rows = cumulative_table()
    data = read_measured_wear(write_csv(tmp_path / "few.csv", rows, columns))
    assert data.available == ("sliding_distance_m", "wear_volume_m3", "normal_load_N")
    assert data.missing == ("pressure_Pa", "velocity_m_s", "time_s", "friction_coefficient",
                            "temperature_C")
    for name in data.missing:
        assert getattr(data, name) is None
    with pytest.raises(FewearInputError, match="contact_area_m2"):
        wear_coefficient_samples(data)
    pressure, velocity, k = wear_coefficient_samples(data, contact_area_m2=AREA_m2)
    assert velocity is None
    np.testing.assert_allclose(pressure, PRESSURE_Pa, rtol=1e-14)
    np.testing.assert_allclose(k, K_m2_N, rtol=1e-12)


def test_one_reading_per_test(tmp_path):
    rows = cumulative_table()[2::3]
    data = read_measured_wear(write_csv(tmp_path / "one.csv", rows))
    assert [len(index) for index in data.tests()] == [1, 1]
    _, _, k = wear_coefficient_samples(data)
    np.testing.assert_allclose(k, K_m2_N, rtol=1e-12)


def test_distance_derived_from_time_and_velocity_is_noted(tmp_path):
    rows = cumulative_table()
    columns = [name for name in rows[0] if name != "sliding_distance_m"]
    data = read_measured_wear(write_csv(tmp_path / "time.csv", rows, columns))
    np.testing.assert_allclose(data.sliding_distance_m, column(rows, "sliding_distance_m"),
                               rtol=1e-14)
    assert "s = v t" in data.notes[0]


def test_pressure_varying_within_a_test_gives_no_sample(tmp_path):
    rows = cumulative_table()
    rows[1]["pressure_Pa"] = 2e6
    data = read_measured_wear(write_csv(tmp_path / "ramp.csv", rows))
    with pytest.raises(FewearInputError, match="pressure_Pa varies within test run 1"):
        wear_coefficient_samples(data)


# Line numbers: line 1 is the comment, line 2 the header, readings on lines 3 to 8.
BAD_CELLS = [
    (1, "wear_volume_m3", "inf", "line 4, column wear_volume_m3: inf; expected a finite number"),
    (4, "sliding_distance_m", 50.0, "line 7, column sliding_distance_m: 50.0 is less than"),
    (3, "pressure_Pa", float("nan"), "line 6, column pressure_Pa: nan"),
    (0, "velocity_m_s", "fast", "line 3, column velocity_m_s: 'fast' is not a number"),
    (5, "time_s", "", "line 8, column time_s: empty value"),
    (2, "pressure_Pa", 0.0, "line 5, column pressure_Pa: 0.0; expected a positive number"),
    (1, "temperature_C", -300.0, "line 4, column temperature_C: -300.0"),
    (3, "test_id", " ", "line 6, column test_id: empty test name"),
    (4, "material", "bronze", "line 7, column material: 'bronze' differs from 'steel'"),
    (1, "factor_lubrication", " ", "line 4, column factor_lubrication: empty value"),
]


@pytest.mark.parametrize("row, name, value, message", BAD_CELLS)
def test_bad_cells_name_line_and_column(tmp_path, row, name, value, message):
    rows = with_factors(cumulative_table())
    rows[row][name] = value
    with pytest.raises(FewearInputError, match=message):
        read_measured_wear(write_csv(tmp_path / "bad.csv", rows))


BAD_HEADERS = [
    ("wear_volume_m3", "wear_volume_mm3",
     "line 2, column 'wear_volume_mm3': unknown column or unit.*wear_volume_m3"),
    ("pressure_Pa", "pressure_MPa", "column 'pressure_MPa': unknown column or unit.*pressure_Pa"),
    ("temperature_C", "colour", "column 'colour': unknown column; allowed columns"),
    ("wear_volume_m3", None, "line 2: expected exactly one wear column"),
    ("test_id", None, "line 2: missing required column test_id"),
    ("sliding_distance_m", None, "line 2: missing required column sliding_distance_m"),
]


@pytest.mark.parametrize("old, new, message", BAD_HEADERS)
def test_bad_headers_name_the_column(tmp_path, old, new, message):
    rows = cumulative_table()
    if old == "sliding_distance_m":
        for row in rows:
            del row["time_s"]
    for row in rows:
        value = row.pop(old)
        if new is not None:
            row[new] = value
    with pytest.raises(FewearInputError, match=message):
        read_measured_wear(write_csv(tmp_path / "bad.csv", rows))


def test_two_wear_columns_are_ambiguous(tmp_path):
    rows = cumulative_table()
    for row in rows:
        row["mass_loss_kg"] = 1e-6
    with pytest.raises(FewearInputError, match="exactly one wear column.*wear_volume_m3, mass"):
        read_measured_wear(write_csv(tmp_path / "bad.csv", rows), density_kg_m3=8e3)


def test_ragged_row_and_empty_file(tmp_path):
    path = write_csv(tmp_path / "ragged.csv", cumulative_table())
    lines = path.read_text().splitlines()
    lines[4] += ",7"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(FewearInputError, match="line 5: 10 values for the 9 columns"):
        read_measured_wear(path)
    (tmp_path / "empty.csv").write_text("# nothing\n")
    with pytest.raises(FewearInputError, match="no header"):
        read_measured_wear(tmp_path / "empty.csv")
    with pytest.raises(FewearInputError, match="cannot read"):
        read_measured_wear(tmp_path / "absent.csv")


def test_direct_construction_checks_values():
    with pytest.raises(FewearInputError, match="reading 1, column sliding_distance_m.*less than"):
        MeasuredWear(source="memory", data_kind="cumulative_volume", test_id=["a", "a"],
                     sliding_distance_m=[2.0, 1.0], wear_volume_m3=[1e-9, 2e-9])
    with pytest.raises(FewearInputError, match="pressure_Pa has 1 values for 2 readings"):
        MeasuredWear(source="memory", data_kind="cumulative_volume", test_id=["a", "a"],
                     sliding_distance_m=[1.0, 2.0], wear_volume_m3=[1e-9, 2e-9],
                     pressure_Pa=[1e6])


def with_factors(rows):
    """The rows with a material (brass, then steel) and a lubrication factor per test."""
    for row in rows:
        row["material"] = "brass" if row["test_id"] == rows[0]["test_id"] else "steel"
        row["factor_lubrication"] = "dry"
    return rows


def test_readings_that_dip_are_kept_and_counted(tmp_path):
    rows = cumulative_table()
    rows[2]["wear_volume_m3"] = 0.5 * rows[1]["wear_volume_m3"]
    rows[4]["wear_volume_m3"] = 0.5 * rows[3]["wear_volume_m3"]
    data = read_measured_wear(write_csv(tmp_path / "dips.csv", rows))
    np.testing.assert_array_equal(data.wear_volume_m3, column(rows, "wear_volume_m3"))
    assert data.notes == ("2 reading(s) of wear_volume_m3 dip below the previous reading of "
                          "their test: kept as data (the scatter of each reading is modelled, "
                          "not removed)",)


def test_categorical_factors_are_read_as_text_and_written_back(tmp_path):
    rows = with_factors(cumulative_table())
    data = read_measured_wear(write_csv(tmp_path / "factors.csv", rows))
    assert set(data.factors) == {"material", "factor_lubrication"}
    assert list(data.factors["material"]) == [row["material"] for row in rows]
    write_measured_wear(tmp_path / "again.csv", data)
    again = read_measured_wear(tmp_path / "again.csv")
    assert list(again.factors["material"]) == list(data.factors["material"])


def test_wear_rate_per_metre_converts_to_volume(tmp_path):
    rows = [{"test_id": f"S{i}", "normal_load_N": 10.0 * (i + 1),
             "sliding_distance_m": 500.0 * (i + 1), "wear_rate_m3_m": 2e-12 * (i + 1)}
            for i in range(3)]
    data = read_measured_wear(write_csv(tmp_path / "rate.csv", rows))
    assert data.data_kind == "wear_rate"
    np.testing.assert_allclose(data.wear_volume_m3, [1e-9, 4e-9, 9e-9], rtol=1e-15)
    assert "V = (V / s) s" in data.notes[0]


def test_other_names_of_schema_columns_are_read_and_noted(tmp_path):
    rows = cumulative_table()
    for row in rows:
        row["sliding_speed_m_s"] = row.pop("velocity_m_s")
        row["contact_pressure_Pa"] = row.pop("pressure_Pa")
    data = read_measured_wear(write_csv(tmp_path / "aliases.csv", rows))
    np.testing.assert_array_equal(data.velocity_m_s, column(rows, "sliding_speed_m_s"))
    np.testing.assert_array_equal(data.pressure_Pa, column(rows, "contact_pressure_Pa"))
    assert "column sliding_speed_m_s read as velocity_m_s" in data.notes
